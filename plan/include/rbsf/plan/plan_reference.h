#pragma once
/// \file
/// \brief The reference trajectory of a plan, for tracking and replay.

#include "rbsf/dynamics/control/reference_trajectory.h"
#include "rbsf/dynamics/core/sensing.h"
#include "rbsf/plan/plan.h"

namespace rbsf::plan {

/// \brief Knots from the plan's samples (t, q, v; a sample at the time of the previous one
///        is skipped), input pieces from its segments back to back from t = 0 (tau held,
///        or ramped to tau_end when present; the segment's phase).
/// \throws InputError when the plan has no samples or segments, or bad values.
ReferenceTrajectory makeReference(const Plan& plan);

/// \brief The sensing the plan's control law uses on a cell that senses `cell`: the cell's,
///        without the part's pose when the plan holds the part by the joints alone
///        (Plan::joint_feedback; its quasi-static slides are below what the part estimator
///        resolves).
Sensing lawSensing(const Sensing& cell, const Plan& plan);

}  // namespace rbsf::plan
