// Support-refinement benchmark (a program, not a timed test): the default cell's support
// plans of 15, 30 and 45 degree turns and of the quarter turn (+90 degrees onto
// (-0.21, 0.43), one pivot: planner/pivot_turn_search.h at friction use 0.82), each planned
// by the support planner on an expansion budget and refined as plan-reorientation refines it
// (planner::refineAndCertify with the plan's margins: stated roles, friction-use cone, normal
// floor, motion limits, tube, least-norm forces; certify both, write the refinement when its
// certificate is at least the planner's). Per problem: the planner's and the refinement's
// certificates (the same draws), which plan is written, the effort of the refinement over the
// planner's, Ipopt's status and iterations, and the median wall time of --repeats solves of
// the refinement's first NLP (the optimiser alone, without certificates).
//   build/bench/rbsf_support_refine_bench [--knots 100] [--repeats 5] [--trials 0]
//                                         [--only 15|30|45|90] [--tube 0.01]
//                                         [--tube-angle 0.0349] [--slip 0.1]
//                                         [--min-scale 0.5] [--print-level 0]
// --trials 0: the default sequential certificate (batches of 64 up to 512); N: N trials.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_stats.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/pipeline/refine_and_certify.h"
#include "rbsf/planner/support/support_planner.h"
#include "rbsf/tools/tool_main.h"
#include "rbsf/trajopt/plan_refinement.h"

namespace {

struct Case {
  const char* label;
  rbsf::Pose goal;
  bool simple_turn;  ///< search one-pivot turns (the quarter turn)
};

int run(int argc, char** argv) {
  int knots = 100, repeats = 5, trials = 0;
  rbsf::trajopt::OptimizerSettings os;
  std::string only;
  rbsf::trajopt::SupportRefinement support;
  CLI::App app{
      "Support-refinement benchmark: the default cell's 15, 30, 45 and 90 degree support "
      "plans refined on their roles and margins; certificates of both plans on the same draws, "
      "the plan written, effort after / before, Ipopt's iterations and the median solve time.",
      "rbsf_support_refine_bench"};
  app.footer(rbsf::tools::kExitStatusHelp);
  app.add_option("--knots", knots, "collocation intervals (default 100)")
      ->check(CLI::Range(2, 100000));
  app.add_option("--repeats", repeats, "timed solves per plan (default 5)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--trials", trials, "fixed trials per certificate (default 0: sequential)")
      ->check(CLI::Range(0, 100000));
  app.add_option("--only", only, "one problem: 15, 30, 45 or 90")
      ->check(CLI::IsMember({"15", "30", "45", "90"}));
  app.add_option("--tube", support.tube_position, "SupportRefinement::tube_position [m]")
      ->check(CLI::PositiveNumber);
  app.add_option("--tube-angle", support.tube_angle, "SupportRefinement::tube_angle [rad]")
      ->check(CLI::PositiveNumber);
  app.add_option("--slip", support.min_slip_rate, "SupportRefinement::min_slip_rate [1/s]")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--print-level", os.print_level, "Ipopt's print_level (default 0)")
      ->check(CLI::Range(0, 12));
  app.add_option("--min-scale", support.duration_min_scale, "SupportRefinement::duration_min_scale")
      ->check(CLI::Range(0.01, 1.0));
  rbsf::tools::parseCommandLine(app, argc, argv);

  const rbsf::RbsfModel model(rbsf::loadCell(RBSF_SOURCE_DIR "/cells/default.yaml"));
  const double deg = M_PI / 180.0;
  const Case cases[] = {{"15", {0.1, 0.40, -15 * deg}, false},
                        {"30", {0.1, 0.40, -30 * deg}, false},
                        {"45", {0.1, 0.40, -45 * deg}, false},
                        {"90", {-0.21, 0.43, 90 * deg}, true}};
  os.knots = knots;
  os.max_solve_time = 3600.0;  // bounded by iterations: the same result on a loaded machine
  std::printf("%-4s %10s %10s %10s %9s %-22s %6s %14s\n", "turn", "planner", "refined", "written",
              "effort", "Ipopt (iterations)", "solves", "median solve s");
  for (const Case& c : cases) {
    if (!only.empty() && only != c.label) continue;
    rbsf::planner::SupportPlannerSettings ps;
    ps.max_expansions = 100000;
    ps.time_limit = 3600.0;
    if (c.simple_turn) {
      ps.simple_turn_friction_uses = {0.82};
      ps.friction_uses.clear();
    }
    rbsf::planner::SupportPlanner planner(model, ps);
    rbsf::planner::Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = c.goal;
    rbsf::plan::Plan plan;
    if (!planner.solve(p, plan)) {
      std::printf("%-4s no support path (%s)\n", c.label, planner.message().c_str());
      continue;
    }
    if (plan.status != rbsf::plan::PlanStatus::kExact) {
      const rbsf::plan::PlanSample& end = plan.samples.back();
      std::printf(
          "%-4s no exact support plan to refine: the closed-loop run of the path kept "
          "ends %.3f m from the goal%s\n",
          c.label, std::hypot(end.q[0] - c.goal.x, end.q[1] - c.goal.y),
          end.f_n.maxCoeff() > 0.0 ? "" : " (the part dropped)");
      continue;
    }
    const rbsf::plan::PlanMargins margins = planner.margins();
    rbsf::trajopt::RefineSettings rs;
    rs.support = support;
    rbsf::plan::CertificateSettings cs;
    cs.trials = trials;
    const rbsf::trajopt::PlanRefiner refiner(model, os, rs);
    const rbsf::planner::RefinementResult out =
        rbsf::planner::refineAndCertify(refiner, plan, margins, cs);
    const rbsf::plan::OptimizationSummary& o = out.record.optimization;
    // The optimiser alone, timed: the refinement's first solve again.
    const rbsf::trajopt::PlanOptimizer first(
        model, rbsf::trajopt::supportOptimizerSettings(os, margins, support));
    std::vector<double> times;
    rbsf::plan::OptimizationSummary timed;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      timed = first.optimize(plan).summary;
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    auto cert = [](const rbsf::plan::Certificate& k) {
      char text[64];
      std::snprintf(text, sizeof text, "%d/%d %.3f%s", k.successes, k.trials, k.lower_bound,
                    k.certified ? "*" : "");
      return std::string(text);
    };
    const std::string refined =
        out.refined
            ? cert(out.record.certificate)
            : (o.refined_success_rate >= 0.0
                   ? std::to_string(static_cast<int>(std::lround(100 * o.refined_success_rate))) +
                         "%"
                   : "-");
    char ipopt[64];
    std::snprintf(ipopt, sizeof ipopt, "%s (%d)", toString(o.status), o.iterations);
    std::printf("%-4s %10s %10s %10s %9.3f %-22s %6d %14.3f\n", c.label,
                cert(out.planner_certificate).c_str(), refined.c_str(),
                out.refined ? "refined" : "planner's",
                o.cost_before > 0.0 ? o.cost_after / o.cost_before : 1.0, ipopt, out.solves,
                rbsf::bench::median(times));
    std::printf("     timed solve: %s, %d iterations\n", toString(timed.status), timed.iterations);
    if (!out.refined) std::printf("     why: %s\n", out.reason.c_str());
  }
  std::printf(
      "certificates: successes/trials, 95 %% lower bound, * certified; effort: of the "
      "summarised solve, after / before\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf_support_refine_bench", argc, argv, run);
}
