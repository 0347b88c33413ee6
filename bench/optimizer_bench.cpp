// One optimiser solve: PlanOptimizer::optimize (direct collocation, Ipopt with MUMPS) on the
// planner's plan of a 15 degree turn of the default part (seed 7, as the trajopt tests),
// with 40 collocation intervals (the tests' setting) and with the default 100. The plan is
// made once; each iteration is a whole solve from the plan. Counters: Ipopt iterations and
// whether it converged (1) or not (0).
#include <benchmark/benchmark.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "rbsf/planner/reorientation_planner.h"
#include "rbsf/trajopt/plan_optimizer.h"

namespace rbsf {
namespace {

const RbsfModel& benchModel() {
  static const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  return model;
}

const planner::Plan& shortPlan() {
  static const planner::Plan plan = [] {
    planner::PlannerSettings s;
    s.seed = 7;
    s.time_limit = 120.0;
    planner::ReorientationPlanner planner(benchModel(), s);
    planner::Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
    planner::Plan out;
    if (!planner.solve(p, out)) throw std::runtime_error("no plan for the 15 degree turn");
    return out;
  }();
  return plan;
}

void BM_OptimizerSolve(benchmark::State& state) {
  trajopt::OptimizerSettings s;
  s.knots = static_cast<int>(state.range(0));
  const trajopt::PlanOptimizer optimizer(benchModel(), s);
  const planner::Plan& plan = shortPlan();
  trajopt::OptimizedPlan out;
  for (auto _ : state) {
    out = optimizer.optimize(plan);
    benchmark::DoNotOptimize(out.plan.segments.data());
  }
  state.counters["ipopt_iterations"] = out.plan.optimization.iterations;
  state.counters["converged"] = out.success ? 1 : 0;
  state.counters["segments"] = static_cast<double>(plan.segments.size());
}
BENCHMARK(BM_OptimizerSolve)->ArgName("knots")->Arg(40)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rbsf
