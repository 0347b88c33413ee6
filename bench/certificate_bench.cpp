// Certificate benchmark (a program, not a timed test): the default suite's problems
// (cells/problems/default.yaml: 30, 90, 180 degrees), planned with seeds first-seed..,
// each exact plan refined once by the optimiser, and both plans certified (the sequential
// certificate by default, or --trials closed-loop trials; seed 1) under the part-feedback
// law (the cell's sensing) and the joint-feedback law (the same cell with part_pose:
// none), the same draws for both. A line per plan (success rates, worst trial) and per
// problem a summary: plans found, certified plans of each kind and law, median success
// rate, median wall time and trial count of a certificate.
//   build/bench/rbsf_certificate_bench [--seeds 8] [--first-seed 1] [--trials N]
//                                      [--trial-batch 64] [--max-trials 512]
//                                      [--time-limit 30] [--knots 100] [--only 30|90|180]
//                                      [--problems cells/problems/default.yaml]
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
#include "rbsf/plan/certificate.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"
#include "rbsf/tools/certificate_options.h"
#include "rbsf/tools/tool_main.h"
#include "rbsf/trajopt/plan_optimizer.h"

namespace {

using Clock = std::chrono::steady_clock;

using rbsf::bench::median;

struct Row {
  double rate[2][2] = {{NAN, NAN}, {NAN, NAN}};  ///< [planner, refined][part, joint]
  bool certified[2][2] = {};
};

int run(int argc, char** argv) {
  int seeds = 8, first_seed = 1, knots = 100;
  rbsf::tools::CertificateOptions certificate;
  double time_limit = 30.0;
  std::string only, suite = std::string(RBSF_SOURCE_DIR) + "/cells/problems/default.yaml";
  CLI::App app{
      "Certificate benchmark: each problem's plans (seeds first-seed..) and their refinements "
      "certified under part feedback and joint feedback; success rates per plan and a "
      "summary per problem.",
      "rbsf_certificate_bench"};
  app.footer(rbsf::tools::kExitStatusHelp);
  app.add_option("--seeds", seeds, "planner seeds per problem (default 8)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--first-seed", first_seed, "first seed (default 1)")
      ->check(CLI::Range(1, 1 << 30));
  certificate.addTo(app);
  app.add_option("--time-limit", time_limit, "planner time limit per plan [s] (default 30)")
      ->check(CLI::PositiveNumber);
  app.add_option("--knots", knots, "optimiser collocation intervals (default 100)")
      ->check(CLI::Range(2, 100000));
  app.add_option("--only", only, "one problem by name (e.g. 180deg)");
  app.add_option("--problems", suite, "problem file (default cells/problems/default.yaml)");
  rbsf::tools::parseCommandLine(app, argc, argv);
  rbsf::plan::CertificateSettings base;
  certificate.apply(base);

  const std::vector<rbsf::bench::BenchProblem> problems = rbsf::bench::loadProblemSuite(suite);
  std::printf("%-8s %4s %-9s %13s %13s %13s %13s  %s\n", "problem", "seed", "phases", "plan part",
              "plan joint", "refined part", "refined joint", "worst (planner, part)");
  for (const rbsf::bench::BenchProblem& bp : problems) {
    if (!only.empty() && bp.name != only) continue;
    const rbsf::Cell cell = rbsf::loadCell(bp.cell_path);
    rbsf::Cell blind = cell;
    blind.sensing.part_pose.present = false;
    const rbsf::RbsfModel model(cell), joints_only(blind);
    std::vector<Row> rows;
    std::vector<double> cert_time, cert_trials, rates[2][2];
    int found = 0;
    for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
      rbsf::planner::PlannerSettings ps;
      ps.seed = static_cast<std::uint32_t>(seed);
      ps.time_limit = time_limit;
      rbsf::planner::ReorientationPlanner planner(model, ps);
      rbsf::plan::Plan plan;
      if (!planner.solve(bp.problem, plan) || plan.status != rbsf::plan::PlanStatus::kExact) {
        std::printf("%-8s %4d no exact plan in %.0f s\n", bp.name.c_str(), seed, time_limit);
        continue;
      }
      ++found;
      rbsf::trajopt::OptimizerSettings os;
      os.knots = knots;
      const rbsf::trajopt::OptimizedPlan refined =
          rbsf::trajopt::PlanOptimizer(model, os).optimize(plan);
      rbsf::plan::CertificateSettings cs = base;
      cs.trial.position_tolerance = bp.problem.tolerance.position;
      cs.trial.angle_tolerance = bp.problem.tolerance.angle;
      Row row;
      rbsf::plan::Certificate worst;
      for (int kind = 0; kind < 2; ++kind) {
        if (kind == 1 && !refined.success) continue;
        const rbsf::plan::Plan& p = kind == 0 ? plan : refined.plan;
        for (int law = 0; law < 2; ++law) {
          const auto t0 = Clock::now();
          const rbsf::plan::Certificate c =
              rbsf::plan::certify(law == 0 ? model : joints_only, p, cs);
          if (law == 0) {
            cert_time.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
            cert_trials.push_back(c.trials);
          }
          row.rate[kind][law] = c.success_rate;
          row.certified[kind][law] = c.certified;
          rates[kind][law].push_back(c.success_rate);
          if (kind == 0 && law == 0) worst = c;
        }
      }
      auto cellText = [&](int kind, int law) {
        char buf[32];
        if (std::isnan(row.rate[kind][law]))
          std::snprintf(buf, sizeof buf, "%13s", "-");
        else
          std::snprintf(buf, sizeof buf, "%9.0f %%%s", 100 * row.rate[kind][law],
                        row.certified[kind][law] ? " C" : "  ");
        return std::string(buf);
      };
      std::printf("%-8s %4d %-9s %s %s %s %s  %s\n", bp.name.c_str(), seed,
                  plan.phaseSequence().substr(0, 9).c_str(), cellText(0, 0).c_str(),
                  cellText(0, 1).c_str(), cellText(1, 0).c_str(), cellText(1, 1).c_str(),
                  rbsf::plan::worstTrialText(worst).c_str());
      std::fflush(stdout);
      rows.push_back(row);
    }
    auto count = [&](int kind, int law) {
      int n = 0;
      for (const Row& r : rows) n += r.certified[kind][law] ? 1 : 0;
      return n;
    };
    std::printf(
        "%-8s summary: %d/%d plans; certified (part / joint feedback): planner %d / %d, "
        "refined %d / %d of %zu; median success rate planner %.0f / %.0f %%, refined "
        "%.0f / %.0f %%; median certificate %.3f s, %.0f trials\n",
        bp.name.c_str(), found, seeds, count(0, 0), count(0, 1), count(1, 0), count(1, 1),
        rates[1][0].size(), 100 * median(rates[0][0]), 100 * median(rates[0][1]),
        100 * median(rates[1][0]), 100 * median(rates[1][1]), median(cert_time),
        median(cert_trials));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf_certificate_bench", argc, argv, run);
}
