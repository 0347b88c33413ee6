#pragma once
/// \file
/// \brief The public face of rbsf::trajopt: refine a planner's plan into smooth torques
///        tau(t) by direct collocation on its phase schedule, solved by Ipopt.
///
/// The NLP is documented in the headers of its elements, the decision-vector layout in
/// decision_layout.h and the settings in optimizer_settings.h.

#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/plan/optimization_summary.h"
#include "rbsf/plan/plan.h"
#include "rbsf/trajopt/optimizer_settings.h"

namespace rbsf::trajopt {

/// \brief The optimised plan and how the solve went. Never throws for a solver failure:
///        `summary` says what happened and `plan` is then the input plan.
struct OptimizedPlan {
  bool success = false;  ///< Ipopt converged (Solve_Succeeded or Solved_To_Acceptable_Level)
  plan::Plan plan;       ///< refined segments (tau ramps, see PlanSegment::tau_end) and samples
  plan::OptimizationSummary summary;  ///< the solve (status, iterations, costs, time)
  /// \brief On success, per sample (knot) of `plan`: the tangential contact forces f_t [N]
  ///        (along t_i, non-zero only where sticking; like the samples' f_n, the knot's
  ///        own) and the foot-point parameters xi.
  std::vector<VecC> f_t, xi;
};

/// \brief Direct-collocation refinement of plans for one cell.
class PlanOptimizer {
 public:
  /// \throws InputError for bad settings.
  PlanOptimizer(const RbsfModel& model, OptimizerSettings settings = {});

  /// \brief Refine `plan` (made by the planner for this model's cell). When `cancel` is
  ///        given and becomes true, Ipopt stops at its next iteration (status
  ///        "User_Requested_Stop") and the input plan is returned.
  /// \throws InputError when the plan does not belong to the model (dimensions).
  OptimizedPlan optimize(const plan::Plan& plan, const std::atomic<bool>* cancel = nullptr) const;

  const RbsfModel& model() const { return model_; }
  const OptimizerSettings& settings() const { return settings_; }

 private:
  const RbsfModel& model_;
  OptimizerSettings settings_;
};

}  // namespace rbsf::trajopt
