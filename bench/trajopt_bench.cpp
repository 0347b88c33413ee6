// Optimiser benchmark (a program, not a timed test): the default cell's 30, 90 and 180
// degree reorientations through the product's pipeline call (ReorientationPipeline: one
// KPIECE1 search per seed 1..N), each exact plan refined by the pipeline's refinement step
// (planner::refineAndCertify, --knots collocation intervals: optimise, certify the planner's
// plan and the refinement, retry once with a minimum slip rate when the refinement is not
// certified, keep the better). Per problem: plans found, Ipopt converged
// (the summarised solve), median iterations, median and worst solve time (wall), the median
// CPU time of the whole refinement with its certificates (which the machine's load affects
// less), median effort reduction 1 - integral(tau^T W tau) after / before over converged
// solves, refinements kept, kept plans certified, and the median effort of the plan kept
// (written) over the planner's: after / before when the refinement is kept, else 1.
//   build/bench/rbsf_trajopt_bench [--seeds 5] [--first-seed 1] [--knots 100]
//                                  [--time-limit 30] [--max-solve-time 30] [--verbose 1]
//                                  [--only 30|90|180] [--force-weight 1e-3]
//                                  [--smoothness 0.01] [--slide-direction 1]
//                                  [--split-runs 0] [--tolerance 1e-6]
// (--help lists them; bad input exits 2 with one message naming the option.)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <variant>
#include <vector>

#include "bench_stats.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/pipeline/reorientation_pipeline.h"
#include "rbsf/tools/tool_main.h"
#include "rbsf/trajopt/plan_optimizer.h"
#include "rbsf/trajopt/plan_refinement.h"

namespace {
using rbsf::bench::median;

int run(int argc, char** argv) {
  int seeds = 5, knots = 100, verbose = 0, first_seed = 1;
  std::string only;
  double time_limit = 30.0, max_time = 30.0;
  rbsf::trajopt::OptimizerSettings os;
  int keep_slide_direction = os.keep_slide_direction ? 1 : 0;
  int split_runs = os.split_runs_by_contact_modes ? 1 : 0;
  CLI::App app{
      "Optimiser benchmark: the default cell's 30, 90 and 180 degree reorientations planned "
      "with seeds first-seed.. (KPIECE1), each plan refined as plan-reorientation refines it "
      "(optimise, certify, retry, keep the better); per problem plans found, converged, median "
      "iterations, median and worst solve time, median CPU time of the refinement, median "
      "effort reduction, refinements kept, kept plans certified, median effort kept/planned.",
      "rbsf_trajopt_bench"};
  app.footer(rbsf::tools::kExitStatusHelp);
  app.add_option("--seeds", seeds, "planner seeds per problem (default 5)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--first-seed", first_seed, "first seed (default 1)")
      ->check(CLI::Range(1, 1 << 30));
  app.add_option("--knots", knots, "collocation intervals (default 100)")
      ->check(CLI::Range(2, 100000));
  app.add_option("--time-limit", time_limit, "planner time limit per plan [s] (default 30)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-solve-time", max_time, "optimiser wall-time limit [s] (default 30)")
      ->check(CLI::PositiveNumber);
  app.add_option("--verbose", verbose, "1: a line per plan (default 0)")->check(CLI::Range(0, 1));
  app.add_option("--only", only, "one problem: 30, 90 or 180")
      ->check(CLI::IsMember({"30", "90", "180"}));
  app.add_option("--force-weight", os.force_weight, "OptimizerSettings::force_weight")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--smoothness", os.smoothness_weight, "OptimizerSettings::smoothness_weight")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--slide-direction", keep_slide_direction,
                 "OptimizerSettings::keep_slide_direction, 0 or 1")
      ->check(CLI::Range(0, 1));
  app.add_option("--split-runs", split_runs,
                 "OptimizerSettings::split_runs_by_contact_modes, 0 or 1")
      ->check(CLI::Range(0, 1));
  app.add_option("--tolerance", os.tolerance, "OptimizerSettings::tolerance (Ipopt tol)")
      ->check(CLI::PositiveNumber);
  rbsf::tools::parseCommandLine(app, argc, argv);
  os.knots = knots;
  os.max_solve_time = max_time;
  os.keep_slide_direction = keep_slide_direction != 0;
  os.split_runs_by_contact_modes = split_runs != 0;

  const rbsf::RbsfModel model(rbsf::loadCell(RBSF_SOURCE_DIR "/cells/default.yaml"));
  struct Case {
    const char* label;
    rbsf::Pose goal;
  };
  const double deg = M_PI / 180.0;
  const Case cases[] = {{"30 deg", {0.1, 0.40, -30 * deg}},
                        {"90 deg", {-0.1, 0.40, -90 * deg}},
                        {"180 deg", {-0.1, 0.40, 180 * deg}}};
  rbsf::trajopt::PlanOptimizer(model, os);  // bad settings: exit 2 before any search
  std::printf("%-8s %6s %9s %5s %10s %9s %8s %10s %6s %9s %10s  (knots %d, %d seeds)\n", "problem",
              "plans", "converged", "iter", "median[s]", "worst[s]", "cpu[s]", "effort -%", "kept",
              "certified", "kept/plan", knots, seeds);
  for (const Case& c : cases) {
    std::vector<double> times, cpu_times, iters, reductions, kept_effort;
    int plans = 0, converged = 0, kept = 0, certified = 0;
    if (!only.empty() && std::string(c.label).rfind(only + " ", 0) != 0) continue;
    for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
      // The product's pipeline call, one kinodynamic search with this seed, whose exact plan
      // is refined (the refinement step reports its outcome and is timed).
      rbsf::planner::PipelineSettings ps;
      ps.method = rbsf::planner::PipelineMethod::kKinodynamic;
      ps.max_attempts = 1;
      ps.planner.seed = static_cast<std::uint32_t>(seed);
      ps.planner.time_limit = time_limit;
      ps.optimize = true;
      ps.optimizer = os;
      rbsf::planner::RefinementResult out;
      bool refined = false;
      double cpu = 0.0;
      std::clock_t cpu0 = 0;
      std::string planned_phases;  // of the planner's plan, which the step refines
      std::size_t planned_segments = 0;
      rbsf::planner::RunContext context;
      context.on_event = [&](const rbsf::planner::PipelineEvent& e) {
        if (const auto* found = std::get_if<rbsf::planner::PlanFound>(&e)) {
          planned_phases = found->plan.phaseSequence();
          planned_segments = found->plan.segments.size();
        } else if (const auto* stage = std::get_if<rbsf::planner::StageStarted>(&e)) {
          if (stage->stage == rbsf::planner::PipelineStage::kRefining) cpu0 = std::clock();
        } else if (const auto* r = std::get_if<rbsf::planner::PlanRefined>(&e)) {
          cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
          out = r->refinement;
          refined = true;
        }
      };
      rbsf::planner::Problem p;
      p.start = {0.1, 0.40, 0.0};
      p.goal = c.goal;
      rbsf::planner::ReorientationPipeline pipeline(model, ps);
      pipeline.run(p, context);
      if (!refined) continue;  // no exact plan: nothing to refine
      ++plans;
      cpu_times.push_back(cpu);
      const rbsf::plan::OptimizationSummary& o = out.record.optimization;
      if (verbose)
        std::printf(
            "  seed %d: %s (%s, %zu segments) %s, %d iterations, %.3f s (refinement cpu %.3f "
            "s), effort %.4f -> %.4f, %s, %s %s\n",
            seed, c.label, planned_phases.c_str(), planned_segments, toString(o.status),
            o.iterations, o.solve_time, cpu, o.cost_before, o.cost_after,
            out.refined ? "refinement kept" : "planner's plan kept",
            out.record.certificate.certified ? "certified" : "not certified", o.message.c_str());
      times.push_back(o.solve_time);
      iters.push_back(o.iterations);
      if (out.converged) {
        ++converged;
        reductions.push_back(100.0 * (1.0 - o.cost_after / o.cost_before));
      }
      kept += out.refined;
      certified += out.record.certificate.certified;
      kept_effort.push_back(out.refined && o.cost_before > 0.0 ? o.cost_after / o.cost_before
                                                               : 1.0);
    }
    char a[32], b[32], k[32], cf[32];
    std::snprintf(a, sizeof a, "%d/%d", plans, seeds);
    std::snprintf(b, sizeof b, "%d/%d", converged, plans);
    std::snprintf(k, sizeof k, "%d/%d", kept, plans);
    std::snprintf(cf, sizeof cf, "%d/%d", certified, plans);
    std::printf("%-8s %6s %9s %5.0f %10.3f %9.3f %8.3f %10.1f %6s %9s %10.2f\n", c.label, a, b,
                median(iters), median(times),
                times.empty() ? NAN : *std::max_element(times.begin(), times.end()),
                median(cpu_times), median(reductions), k, cf, median(kept_effort));
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf_trajopt_bench", argc, argv, run);
}
