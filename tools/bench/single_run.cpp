#include "rbsf/bench/single_run.h"

#include <cmath>
#include <string>

#include <ompl/control/PathControl.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "rbsf/bench/benchmark_log.h"

namespace rbsf::bench {

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// Propagations OMPL's PathControl::check() makes on a correct path: each control
/// re-propagated step by step (propagateWhileValid), floor(0.5 + duration / step) calls.
std::uint64_t checkPropagations(const oc::PathControl& path, double step) {
  std::uint64_t n = 0;
  for (std::size_t k = 0; k < path.getControlCount(); ++k)
    n += static_cast<std::uint64_t>(std::floor(0.5 + path.getControlDuration(k) / step));
  return n;
}

}  // namespace

void runSingle(const BenchProblem& bp, const RbsfModel& model, const RunSpec& spec,
               const RunSettings& rs, const std::string& log_path) {
  ompl::RNG::setSeed(spec.seed);
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  planner::PlannerSettings s;
  s.planner = spec.planner;
  s.time_limit = rs.time_limit;
  s.seed = spec.seed;
  s.position_tolerance = bp.position_tolerance;
  s.angle_tolerance = bp.angle_tolerance;
  planner::ReorientationPlanner rp(model, s);
  const planner::PlannerSetup setup = rp.setup(bp.problem);
  oc::SimpleSetup& ss = *setup.simple_setup;

  ompl::tools::Benchmark benchmark(ss, bp.name);
  benchmark.addPlanner(ss.getPlanner());
  benchmark.setPostRunEvent([&](const ob::PlannerPtr&, ompl::tools::Benchmark::RunProperties& run) {
    run["run index INTEGER"] = std::to_string(spec.run);
    run["seed INTEGER"] = std::to_string(spec.seed);
    const ob::ProblemDefinitionPtr& pdef = ss.getProblemDefinition();
    const ob::PathPtr path = pdef->getSolutionPath();
    std::uint64_t check = 0;
    const auto correct = run.find("correct solution BOOLEAN");
    if (path && correct != run.end() && correct->second == "1")
      check = checkPropagations(static_cast<const oc::PathControl&>(*path),
                                ss.getSpaceInformation()->getPropagationStepSize());
    const std::uint64_t props = setup.propagator->propagations() - check;
    const std::uint64_t steps =
        setup.propagator->steps() - check * static_cast<std::uint64_t>(s.steps_per_control);
    const double time = std::stod(run["time REAL"]);
    run["propagations INTEGER"] = std::to_string(props);
    run["simulator steps INTEGER"] = std::to_string(steps);
    if (time > 0.0) run["propagations per second REAL"] = num(static_cast<double>(props) / time);
    if (std::isfinite(setup.goal->bestDistance()))
      run["best goal distance REAL"] = num(setup.goal->bestDistance());
    if (!pdef->hasExactSolution()) return;
    planner::Plan plan;
    if (!rp.makePlan(bp.problem, setup, time, plan)) return;
    run["solution duration REAL"] = num(plan.duration());
    run["path mismatch REAL"] = num(plan.path_mismatch);
  });
  // One run, no console output, no path simplification (geometric only).
  const ompl::tools::Benchmark::Request request(rs.time_limit, 4096.0, 1, 0.05, false, false,
                                                false);
  benchmark.benchmark(request);
  std::ostringstream text;
  if (!benchmark.saveResultsToStream(text))
    throw std::runtime_error("OMPL's benchmark recorded no run");
  writeFileAtomically(log_path, text.str());
}

}  // namespace rbsf::bench
