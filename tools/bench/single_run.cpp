#include "rbsf/bench/single_run.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/control/PathControl.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "rbsf/bench/benchmark_log.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/planner/pipeline/refine_and_certify.h"
#include "rbsf/planner/pipeline/support_ompl_planner.h"
#include "rbsf/trajopt/plan_optimizer.h"
#include "rbsf/trajopt/plan_refinement.h"

namespace rbsf::bench {

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace {

/// A BOOLEAN column's value.
std::string flag(bool b) { return b ? "1" : "0"; }

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

using RunProperties = ompl::tools::Benchmark::RunProperties;

/// The planner's settings of a run: the support planner runs on the same setup, its
/// propagation step a support plan's control period and without the kinodynamic search's
/// decisive-modes rule (support_ompl_planner.h); the setup's own planner is then replaced.
planner::PlannerSettings runSettings(const RunSpec& spec, const RunSettings& rs, bool support) {
  planner::PlannerSettings s;
  s.planner =
      support ? planner::KinodynamicPlanner::kKPIECE1 : *planner::parsePlanner(spec.planner);
  if (support) {
    s.steps_per_control = planner::SupportOmplPlanner::kControlSteps;
    s.decisive_modes.enabled = false;
  }
  s.time_limit = rs.time_limit;
  s.seed = spec.seed;
  return s;
}

/// rbsf's columns exist in every run (empty: NULL), also when no run solved.
void addEmptyColumns(RunProperties& run, bool optimize) {
  for (const char* key : {"best goal distance REAL", "solution duration REAL", "path mismatch REAL",
                          "expansions INTEGER", "pivots INTEGER"})
    run[key] = "";
  if (optimize)
    for (const char* key :
         {"optimizer success BOOLEAN", "optimizer status ENUM", "optimizer iterations INTEGER",
          "optimizer time REAL", "cost before REAL", "cost after REAL", "cost reduction REAL",
          "refined chosen BOOLEAN", "certified BOOLEAN", "certificate success rate REAL",
          "certificate lower bound REAL", "certificate trials INTEGER"})
      run[key] = "";
}

/// The refinement's columns: the optimiser's solve and the certificate of the plan kept.
void addRefinementColumns(RunProperties& run, const planner::RefinementResult& out) {
  const plan::OptimizationSummary& o = out.record.optimization;
  run["optimizer success BOOLEAN"] = flag(out.converged);
  run["optimizer status ENUM"] = std::to_string(static_cast<int>(o.status));
  run["optimizer iterations INTEGER"] = std::to_string(o.iterations);
  run["optimizer time REAL"] = num(o.solve_time);
  if (std::isfinite(o.cost_before)) run["cost before REAL"] = num(o.cost_before);
  if (out.converged && std::isfinite(o.cost_after)) {
    run["cost after REAL"] = num(o.cost_after);
    if (o.cost_before > 0.0) run["cost reduction REAL"] = num(1.0 - o.cost_after / o.cost_before);
  }
  run["refined chosen BOOLEAN"] = flag(out.refined);
  run["certified BOOLEAN"] = flag(out.record.certificate.certified);
  run["certificate success rate REAL"] = num(out.record.certificate.success_rate);
  run["certificate lower bound REAL"] = num(out.record.certificate.lower_bound);
  run["certificate trials INTEGER"] = std::to_string(out.record.certificate.trials);
}

/// OMPL's log of the benchmark's one run, with the optimiser's status names, to `log_path`.
void writeRunLog(const ompl::tools::Benchmark& benchmark, bool optimize,
                 const std::string& log_path) {
  std::ostringstream text;
  if (!benchmark.saveResultsToStream(text))
    throw std::runtime_error("OMPL's benchmark recorded no run");
  ExperimentLog log = parseLog(text.str(), "OMPL's benchmark log");
  if (optimize) {
    std::string e = "optimizer status";
    for (plan::SolverStatus status : plan::solverStatuses())
      e += std::string("|") + toString(status);
    log.enums.push_back(e);
  }
  writeFileAtomically(log_path, formatLog(log), "--out");
}

}  // namespace

void runSingle(const BenchProblem& bp, const RbsfModel& model, const RunSpec& spec,
               const RunSettings& rs, const std::string& log_path) {
  ompl::RNG::setSeed(spec.seed);
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const bool support = spec.planner == kSupportPlanner;
  const planner::PlannerSettings s = runSettings(spec, rs, support);
  planner::ReorientationPlanner rp(model, s);
  const planner::PlannerSetup setup = rp.setup(bp.problem);
  oc::SimpleSetup& ss = *setup.simple_setup;
  std::shared_ptr<planner::SupportOmplPlanner> support_planner;
  if (support) {
    support_planner =
        std::make_shared<planner::SupportOmplPlanner>(ss.getSpaceInformation(), model);
    ss.setPlanner(support_planner);
  }

  ompl::tools::Benchmark benchmark(ss, bp.name);
  benchmark.addPlanner(ss.getPlanner());
  benchmark.setPostRunEvent([&](const ob::PlannerPtr&, RunProperties& run) {
    addEmptyColumns(run, rs.optimize);
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
    if (support) {  // its propagations only replay its plan into the path
      run["propagations INTEGER"] = "0";
      run["expansions INTEGER"] = std::to_string(support_planner->expansions());
    }
    if (!pdef->hasExactSolution()) return;
    plan::Plan plan;
    if (support)
      plan = support_planner->lastPlan();
    else if (!rp.makePlan(bp.problem, setup, time, plan))
      return;
    run["solution duration REAL"] = num(plan.duration());
    run["path mismatch REAL"] = num(plan.path_mismatch);
    run["pivots INTEGER"] = std::to_string(plan.pivots());
    if (!rs.optimize) return;
    // The product's refinement after the run (OMPL's time is the planner's alone): optimise,
    // certify the planner's plan and the refinement, keep the better (refine_and_certify.h).
    const trajopt::PlanRefiner refiner(model, trajopt::OptimizerSettings{});
    addRefinementColumns(
        run, planner::refineAndCertify(refiner, plan,
                                       support ? support_planner->margins() : plan::PlanMargins{},
                                       plan::CertificateSettings{}));
  });
  // One run, no console output, no path simplification (geometric only).
  const ompl::tools::Benchmark::Request request(rs.time_limit, 4096.0, 1, 0.05, false, false,
                                                false);
  benchmark.benchmark(request);
  writeRunLog(benchmark, rs.optimize, log_path);
}

}  // namespace rbsf::bench
