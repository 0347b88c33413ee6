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
  int attempts = 0;    ///< solves run (1, or 2 with the retry)
};

/// \brief How refinePlan tries.
struct RefineSettings {
  /// \brief When the first refinement is not accepted, solve once more with
  ///        OptimizerSettings::min_slip_rate = this [1/s] (0 or the optimiser's own value:
  ///        no retry). A minimum slip rate keeps sliding contacts clearly sliding, which
  ///        some plans need to replay their phases and which makes others infeasible
  ///        (BENCHMARKS.md, "Forces held per interval"); so it is the second try.
  double retry_min_slip_rate = 0.1;
};

/// \brief Optimise `plan` with `optimizer`; on success verify it (planner::verifyPlan);
///        if not accepted, retry once as RefineSettings says (not after a cancel).
///        Accepted: the refined plan with `optimization` (of the accepted solve; its
///        message names the retry when that was the one), `replay`, accepted = true.
///        Otherwise: the planner's plan with `optimization` of the first solve (message =
///        the reason, both solves' when retried), the replay of the first optimised plan
///        when it ran, accepted = false, and `planner_replay`: the planner's plan verified
///        by the same rule (left out if that replay diverges). Every number in the
///        summaries is finite (a non-finite one is reported in the reason and zeroed).
RefineOutcome refinePlan(const PlanOptimizer& optimizer, const Simulator& simulator,
                         const planner::Plan& plan, const planner::ReplaySettings& replay,
                         const RefineSettings& settings = {});

}  // namespace rbsf::trajopt
