// Temporary: the API compiles and links; the NLP follows in the next commits.
#include "rbsf/trajopt/plan_optimizer.h"

#include "rbsf/dynamics/errors.h"

namespace rbsf::trajopt {

PlanOptimizer::PlanOptimizer(const RbsfModel& model, OptimizerSettings settings)
    : model_(model), settings_(std::move(settings)) {}

OptimizedPlan PlanOptimizer::optimize(const planner::Plan& plan) const {
  OptimizedPlan out;
  out.plan = plan;
  out.plan.optimization.ran = true;
  out.plan.optimization.status = "Not_Implemented";
  out.plan.optimization.message = "optimiser not implemented yet (branch opt in progress)";
  return out;
}

}  // namespace rbsf::trajopt
