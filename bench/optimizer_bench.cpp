// One optimiser solve: PlanOptimizer::optimize (direct collocation, Ipopt with MUMPS) on the
// planner's plan of a 15 degree turn of the default part (seed 7, as the trajopt tests),
// with 40 collocation intervals (the tests' setting) and with the default 100. The plan is
// made once; each iteration is a whole solve from the plan. Counters: Ipopt iterations and
// whether it converged (1) or not (0).
#include <benchmark/benchmark.h>

#include "rbsf/trajopt/plan_optimizer.h"
#include "trajopt_support.h"  // tests/unit: the default cell and the 15 degree plan

namespace rbsf {
namespace {

void BM_OptimizerSolve(benchmark::State& state) {
  trajopt::OptimizerSettings s;
  s.knots = static_cast<int>(state.range(0));
  const trajopt::PlanOptimizer optimizer(trajopt::test::defaultModel(), s);
  const plan::Plan& plan = trajopt::test::shortPlan();
  trajopt::OptimizedPlan out;
  for (auto _ : state) {
    out = optimizer.optimize(plan);
    benchmark::DoNotOptimize(out.plan.segments.data());
  }
  state.counters["ipopt_iterations"] = out.summary.iterations;
  state.counters["converged"] = out.success ? 1 : 0;
  state.counters["segments"] = static_cast<double>(plan.segments.size());
}
BENCHMARK(BM_OptimizerSolve)->ArgName("knots")->Arg(40)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rbsf
