// Pipeline benchmark (a program, not a timed test): every problem of a suite, seeds
// first-seed.., through the pipeline plan-reorientation runs (reorientation_pipeline.h:
// support planner, then kinodynamic seeds, refinement, certificate) on each problem's cell
// as given and on the same cell with part_pose: none (the joint law). A line per run (how
// it ended, the plan kept, its success rate, phase runs and wall time) and per problem and
// law a summary: problem-seed pairs that end certified, the median success rate of the
// certified plans, the median wall time. The goals of BENCHMARKS.md's pipeline table.
//   build/bench/rbsf_pipeline_bench [--seeds 8] [--first-seed 1] [--trials N]
//                                   [--trial-batch 64] [--max-trials 512]
//                                   [--time-limit 30] [--knots 100] [--only 30deg]
//                                   [--law part|joints|both] [--problems FILE]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_stats.h"
#include "rbsf/bench/problem_suite.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/pipeline/reorientation_pipeline.h"
#include "rbsf/tools/certificate_options.h"
#include "rbsf/tools/tool_main.h"
#include "rbsf/trajopt/plan_refinement.h"

namespace {

using rbsf::bench::median;

int run(int argc, char** argv) {
  int seeds = 8, first_seed = 1, knots = 100;
  rbsf::tools::CertificateOptions certificate;
  double time_limit = 30.0;
  std::string only, law = "both", margins = "default",
                    suite = std::string(RBSF_SOURCE_DIR) + "/cells/problems/default.yaml";
  CLI::App app{
      "Pipeline benchmark: each problem and seed planned, refined and certified until a plan "
      "certifies (plan-reorientation's pipeline), under part and joint feedback.",
      "rbsf_pipeline_bench"};
  app.footer(rbsf::tools::kExitStatusHelp);
  app.add_option("--seeds", seeds, "seeds per problem (default 8)")->check(CLI::Range(1, 1000));
  app.add_option("--first-seed", first_seed, "first seed (default 1)")
      ->check(CLI::Range(1, 1 << 30));
  certificate.addTo(app);
  app.add_option("--time-limit", time_limit, "search budget per run [s] (default 30)")
      ->check(CLI::Range(0.01, 1e6));
  app.add_option("--knots", knots, "optimiser collocation intervals (default 100)")
      ->check(CLI::Range(2, 100000));
  app.add_option("--only", only, "one problem by name (e.g. 180deg)");
  app.add_option("--law", law, "part, joints or both (default)")
      ->check(CLI::IsMember({"part", "joints", "both"}));
  app.add_option("--problems", suite, "problem file (default cells/problems/default.yaml)");
  app.add_option("--support-margins", margins,
                 "default, or zero: the support planner's sticking forces anywhere in the "
                 "friction cone and no normal-force floor")
      ->check(CLI::IsMember({"default", "zero"}));
  rbsf::tools::parseCommandLine(app, argc, argv);
  rbsf::plan::CertificateSettings base;
  certificate.apply(base);

  const std::vector<rbsf::bench::BenchProblem> problems = rbsf::bench::loadProblemSuite(suite);
  std::printf("%-9s %-6s %4s %-13s %-20s %8s %6s %8s  %s\n", "problem", "law", "seed", "status",
              "plan kept", "rate", "runs", "wall", "attempts");
  int pairs = 0, certified_pairs = 0;
  for (const rbsf::bench::BenchProblem& bp : problems) {
    if (!only.empty() && bp.name != only) continue;
    const rbsf::Cell cell = rbsf::loadCell(bp.cell_path);
    for (int blind = 0; blind < 2; ++blind) {
      if ((blind == 0 && law == "joints") || (blind == 1 && law == "part")) continue;
      rbsf::Cell c = cell;
      if (blind == 1) c.sensing.part_pose.present = false;
      const rbsf::RbsfModel model(c);
      rbsf::trajopt::OptimizerSettings os;
      os.knots = knots;
      std::vector<double> rates, walls;
      int certified = 0;
      for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
        rbsf::planner::PipelineSettings s;
        s.planner.seed = static_cast<std::uint32_t>(seed);
        s.planner.time_limit = time_limit;
        s.certificate = base;
        if (margins == "zero") {
          s.support.friction_uses = {1.0};
          s.support.search.support.balance.normal_margin = 0.0;
        }
        s.optimize = true;
        s.optimizer = os;
        const rbsf::planner::PipelineOutcome out =
            rbsf::planner::ReorientationPipeline(model, s).run(bp.problem);
        const bool ok = out.status == rbsf::planner::PipelineStatus::kCertified;
        certified += ok ? 1 : 0;
        if (ok) rates.push_back(out.record.certificate.success_rate);
        walls.push_back(out.wall_time);
        std::string kept = "-", tried;
        if (out.chosen >= 0) {
          const rbsf::planner::PipelineAttempt& a = out.attempts[out.chosen];
          const bool support = a.search == rbsf::planner::SearchKind::kSupport;
          kept = a.method() + (support ? "" : " s" + std::to_string(a.seed)) +
                 (a.refined ? " refined" : "");
        }
        for (const rbsf::planner::PipelineAttempt& a : out.attempts) {
          char buf[64];
          const std::string got =
              std::to_string(a.certificate.successes) + "/" + std::to_string(a.certificate.trials);
          std::snprintf(buf, sizeof buf, "%s%s:%s", tried.empty() ? "" : " ",
                        a.search == rbsf::planner::SearchKind::kSupport
                            ? "S"
                            : std::to_string(a.seed).c_str(),
                        !a.found            ? "none"
                        : a.certificate.ran ? got.c_str()
                                            : "?");
          tried += buf;
        }
        std::printf("%-9s %-6s %4d %-13s %-20s %7.0f%% %6zu %7.1fs  %s\n", bp.name.c_str(),
                    blind ? "joints" : "part", seed, rbsf::planner::statusText(out.status),
                    kept.c_str(),
                    out.record.certificate.ran ? 100 * out.record.certificate.success_rate : NAN,
                    out.record.plan.phaseSequence().size(), out.wall_time, tried.c_str());
        std::fflush(stdout);
      }
      pairs += seeds;
      certified_pairs += certified;
      char rate[32] = "-";
      if (!rates.empty()) std::snprintf(rate, sizeof rate, "%.0f %%", 100 * median(rates));
      std::printf(
          "%-9s %-6s summary: %d/%d certified; median success rate of those %s; "
          "median wall %.1f s\n",
          bp.name.c_str(), blind ? "joints" : "part", certified, seeds, rate, median(walls));
    }
  }
  std::printf("all: %d/%d problem-seed pairs certified (%.0f %%)\n", certified_pairs, pairs,
              pairs > 0 ? 100.0 * certified_pairs / pairs : 0.0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf_pipeline_bench", argc, argv, run);
}
