#pragma once
/// \file
/// \brief The optimisation step of plan-reorientation and of the controller facade: optimise
///        an exact plan, replay the result open and closed loop, and keep it only when the
///        replay accepts it.

#include <string>

#include "rbsf/planner/plan_replay.h"
#include "rbsf/trajopt/plan_optimizer.h"

namespace rbsf::trajopt {

/// \brief The plan to write and the verdict.
struct RefineOutcome {
  planner::Plan plan;  ///< the optimised plan if accepted, else the planner's, marked
  bool accepted = false;
  std::string reason;  ///< why not (Ipopt's failure or the failed replay criteria)
};

/// \brief Optimise `plan` with `optimizer`; on success verify it (planner::verifyPlan).
///        Accepted: the refined plan with `optimization`, `replay`, accepted = true.
///        Otherwise: the planner's plan with `optimization` (message = the reason), the
///        replay of the optimised plan when it ran, accepted = false, and
///        `planner_replay`: the planner's plan verified by the same rule (left out if that
///        replay diverges). Every number in the summaries is finite (a non-finite one is
///        reported in the reason and zeroed).
RefineOutcome refinePlan(const PlanOptimizer& optimizer, const Simulator& simulator,
                         const planner::Plan& plan, const planner::ReplaySettings& replay);

}  // namespace rbsf::trajopt
