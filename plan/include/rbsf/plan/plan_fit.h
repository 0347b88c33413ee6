#pragma once
/// \file
/// \brief Whether a plan was made for a cell: a controller runs a plan file only on the
///        cell it was planned and certified for.

#include <string>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/plan/plan.h"
#include "rbsf/plan/plan_file.h"

namespace rbsf::plan {

/// \brief Why `plan` does not fit `model`'s cell, or "" when it does. In order:
///   - sizes: q0, every segment's tau and every sample sized for the cell's fingers;
///   - the recorded cell (Plan::cell, when recorded): each finger's offset r_i, the part's
///     mass and inertia and gravity equal within 1e-9 relative;
///   - the part's shape and the fingers: every finger that carries the part at the plan's
///     first sample has its tip on this cell's part at q0 (gap within 1e-5 m; a finger the
///     plan starts lifted is not asked).
/// One sentence naming what differs, with the plan's value and the cell's.
std::string planCellMismatch(const RbsfModel& model, const Plan& plan);

/// \brief Why the evidence `record` carries does not speak for `model`'s cell, or "" when it
///        does. In order:
///   - friction: the plan's recorded mu_s and mu_k (Plan::cell, when recorded) equal the
///     cell's within 1e-9 relative;
///   - its certificate (when it ran): drawn from the cell's uncertainty (each half-width)
///     under the cell's sensing (joint noise, and the part pose's presence, rate, latency
///     and noise).
/// One sentence naming what differs, with the plan's value and the cell's. A plan without
/// these records (files written before them) is not asked.
std::string certificateCellMismatch(const RbsfModel& model, const PlanRecord& record);

}  // namespace rbsf::plan
