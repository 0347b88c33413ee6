#pragma once
/// \file
/// \brief Whether a plan was made for a cell: a controller runs a plan file only on the
///        cell it was planned and certified for.

#include <string>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/plan/plan.h"

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

}  // namespace rbsf::plan
