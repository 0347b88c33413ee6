// plan-reorientation: torques tau(t) that take the part from where it rests to a goal pose
// (kinodynamic search on OMPL with the hybrid contact simulator as propagator), refined by
// the trajectory optimiser unless --no-optimize, and certified: every plan written is run
// --trials times closed loop under the cell's sensing and uncertainty
// (rbsf/planner/certificate.h); of the planner's plan and the refined plan the one with
// the better certificate is written (rbsf/trajopt/plan_refinement.h).
//
// Exit status: 0 a certified plan written; 4 an exact plan written but not certified
// (verdict and worst trial on stderr); 3 time limit without an exact plan (best distance
// printed; the approximate plan, certified, written); 2 bad input (option, value, cell, a
// start the fingers cannot hold, a goal no finger reaches); 130 stopped by SIGINT (best
// plan so far written, not certified); 1 internal error.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "plan_outputs.h"
#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/state_layout.h"
#include "rbsf/planner/certificate.h"
#include "rbsf/planner/goal.h"
#include "rbsf/planner/reorientation_planner.h"
#include "rbsf/planner/support_planner.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/interrupt.h"
#include "rbsf/tools/tool_main.h"
#include "rbsf/trajopt/plan_refinement.h"

namespace rbsf::tools {
namespace {

constexpr int kExitTimeLimit = 3;
constexpr int kExitNotCertified = 4;

struct Options {
  std::string cell, start, goal,
      start_theta = "0", planner = "KPIECE1", time_limit = "30", seed = "1", out, csv, svg, report,
      svg_still = "0", knots = "100", optimize_time_limit = "30", optimize_iterations = "500",
      optimize_tolerance = "1e-6", goal_angle = "nearest", trials = "32", trial_seed = "1";
  bool quiet = false, no_optimize = false, reproducible = false, no_decisive_modes = false;
};

/// The optimiser's line: which solve, how it went, and whether its plan was chosen.
void printOptimisation(const trajopt::RefineOutcome& r) {
  const planner::OptimizationSummary& o = r.plan.optimization;
  const char* which = r.attempts < 2 ? "" : (r.refined ? " (the retry)" : " (first of 2 solves)");
  std::printf("optimisation%s: %s, %d iterations, %.3f s, cost %.6g -> %.6g\n", which,
              o.status.c_str(), o.iterations, o.solve_time, o.cost_before, o.cost_after);
  std::printf("planner's plan: %s\n", planner::verdictText(r.planner_certificate).c_str());
  if (o.refined_success_rate >= 0.0)
    std::printf("optimised plan: %.0f %% of the trials succeeded\n",
                100.0 * o.refined_success_rate);
  std::printf("written: the %s plan%s\n", r.refined ? "optimised" : "planner's",
              r.refined || o.message.empty() ? "" : (" (" + o.message + ")").c_str());
}

/// The certificate of the plan written: verdict, law and worst trial, in metres and degrees.
void printCertificate(const planner::Certificate& c) {
  std::fputs(planner::certificateReportText(c).c_str(), stdout);
}

int run(int argc, char** argv) {
  CLI::App app{
      "Plan a reorientation of the part: tau segments that take it from rest on the "
      "fingers (placed at --start-theta) to the goal pose within 1 cm and 2 degrees. "
      "Poses: COM x,y [m] and angle (radians, or degrees with a deg suffix).",
      "plan-reorientation"};
  app.footer(
      "Every plan written is certified: replayed --trials times in closed loop under the "
      "cell's sensing and uncertainty (cell keys sensing and uncertainty) and judged by "
      "outcome: the part ends at rest within 1 cm and 2 degrees of the goal, never dropped, "
      "inputs within their limits; certified when 95 % of the trials succeed. Exact plans "
      "are refined by the trajectory optimiser (unless --no-optimize) and the plan with the "
      "better certificate is written.\n"
      "Exit status: 0 a certified plan written; 4 an exact plan written but not certified "
      "(verdict on stderr); 3 time limit without an exact plan (best distance printed; the "
      "approximate plan written); 2 bad input (option, value, file, a start the fingers "
      "cannot hold, a goal no finger reaches), with one message on stderr; 130 stopped by "
      "SIGINT (Ctrl-C, during the search or the optimisation: the best plan so far is "
      "written, not certified; a second Ctrl-C exits at once, writing nothing); 1 internal "
      "error.");
  Options o;
  app.add_option("--cell", o.cell, "cell YAML file")->required();
  app.add_option("--start", o.start, "start pose x,y,phi (part at rest)")->required();
  app.add_option("--goal", o.goal, "goal pose x,y,phi")->required();
  app.add_option("--goal-angle", o.goal_angle,
                 "nearest (default): the goal angle modulo 360 deg, reached whichever way is "
                 "shorter; absolute: the part's total turn from phi = 0, so -270deg asks for "
                 "three quarters of a clockwise turn");
  app.add_option("--start-theta", o.start_theta, "base angle at the start (default 0)");
  app.add_option("--planner", o.planner,
                 "KPIECE1 (default), RRT, SST, EST or PDST (kinodynamic search), or support "
                 "(slow quasi-static supports held by the joints, see README)");
  app.add_option("--time-limit", o.time_limit, "seconds (default 30)");
  app.add_option("--seed", o.seed, "random seed, positive integer (default 1)");
  app.add_option("--out", o.out, "write the plan as JSON");
  app.add_option("--csv", o.csv, "write the sampled trajectory as CSV");
  app.add_option("--svg", o.svg, "write an animated SVG of the plan");
  app.add_option("--report", o.report, "write an HTML page: animation and plots over time");
  app.add_option("--svg-still", o.svg_still, "time [s] of the frame non-animating viewers show");
  app.add_flag("--reproducible", o.reproducible,
               "leave wall-clock fields (planning_time) out of the files: the same seed gives "
               "byte-identical files");
  app.add_flag("--quiet", o.quiet, "no progress line");
  app.add_flag("--no-decisive-modes", o.no_decisive_modes,
               "let contacts change mode anywhere within a held torque (plans a tracking cell "
               "often cannot repeat; see README)");
  app.add_flag("--no-optimize", o.no_optimize, "write the planner's plan without optimising it");
  app.add_option("--knots", o.knots, "collocation intervals of the optimiser (default 100)");
  app.add_option("--optimize-time-limit", o.optimize_time_limit,
                 "optimiser wall-time limit per solve in seconds (default 30)");
  app.add_option("--optimize-iterations", o.optimize_iterations,
                 "optimiser iteration limit (default 500)");
  app.add_option("--optimize-tolerance", o.optimize_tolerance,
                 "optimiser convergence tolerance, Ipopt's tol in (0, 1] (default 1e-6; 1e-4 "
                 "takes about a quarter fewer iterations, see README)");
  app.add_option("--trials", o.trials,
                 "closed-loop trials of the certificate, 1..100000 (default 32)");
  app.add_option("--trial-seed", o.trial_seed,
                 "seed of the certificate's draws, positive integer (default 1)");
  parseCommandLine(app, argc, argv);
  const PlanOutputs outputs({o.out, o.csv, o.svg, o.report, o.reproducible,
                             parseNumber(o.svg_still, "--svg-still"), o.cell});

  const bool support = o.planner == "support";
  planner::PlannerSettings settings;
  settings.planner = support ? "KPIECE1" : o.planner;
  settings.decisive_modes.enabled = !o.no_decisive_modes;
  settings.time_limit = parseNumber(o.time_limit, "--time-limit");
  if (settings.time_limit <= 0.0) throw InputError("--time-limit: must be positive");
  settings.seed = static_cast<std::uint32_t>(parseInteger(o.seed, "--seed", 1, 4294967295LL));
  trajopt::OptimizerSettings opt_settings;
  opt_settings.knots = static_cast<int>(parseInteger(o.knots, "--knots", 2, 100000));
  opt_settings.max_solve_time = parseNumber(o.optimize_time_limit, "--optimize-time-limit");
  if (!(opt_settings.max_solve_time > 0.0))
    throw InputError("--optimize-time-limit: must be positive (got " + o.optimize_time_limit + ")");
  opt_settings.max_iterations =
      static_cast<int>(parseInteger(o.optimize_iterations, "--optimize-iterations", 1, 1000000));
  opt_settings.tolerance = parseNumber(o.optimize_tolerance, "--optimize-tolerance");
  if (!(opt_settings.tolerance > 0.0 && opt_settings.tolerance <= 1.0))
    throw InputError("--optimize-tolerance: must be in (0, 1] (got " + o.optimize_tolerance + ")");
  trajopt::RefineSettings refine;
  planner::CertificateSettings& certificate = refine.certificate;
  certificate.trials = static_cast<int>(parseInteger(o.trials, "--trials", 1, 100000));
  certificate.seed =
      static_cast<std::uint64_t>(parseInteger(o.trial_seed, "--trial-seed", 1, 1LL << 53));
  planner::Problem problem;
  problem.start = parsePose(o.start, "--start");
  problem.goal = parsePose(o.goal, "--goal");
  if (o.goal_angle != "nearest" && o.goal_angle != "absolute")
    throw InputError("--goal-angle: must be nearest or absolute (got " + o.goal_angle + ")");
  problem.absolute_angle = o.goal_angle == "absolute";
  problem.start_theta = parseAngle(o.start_theta, "--start-theta");

  const bool tty = !o.quiet && isatty(fileno(stderr));
  if (tty) {
    settings.progress = [](const planner::Progress& p) {
      std::fprintf(stderr,
                   "\rplan-reorientation: %6.1f s  %10llu propagations  best distance %.3g ",
                   p.elapsed, static_cast<unsigned long long>(p.propagations), p.best_distance);
      std::fflush(stderr);
    };
  }
  const RbsfModel model(loadCell(o.cell));
  settings.cancel = &InterruptFlag::install();  // Ctrl-C: stop and write the best so far
  opt_settings.cancel = settings.cancel;
  planner::ReorientationPlanner rp(model, settings);
  const trajopt::PlanOptimizer optimizer(model, opt_settings);  // bad settings: exit 2
  rp.checkProblem(problem);                                     // bad input before any search
  planner::Plan plan;
  bool found = false;
  if (support) {
    planner::SupportPlannerSettings ss;
    ss.time_limit = settings.time_limit;
    ss.position_tolerance = settings.position_tolerance;
    ss.angle_tolerance = settings.angle_tolerance;
    ss.cancel = settings.cancel;
    planner::SupportPlanner sp(model, ss);
    if (tty) std::fprintf(stderr, "plan-reorientation: searching supports\n");
    found = sp.solve(problem, plan);
    if (InterruptFlag::raised()) {
      std::printf("interrupted: no plan written\n");
      return kExitInterrupted;
    }
    if (!found) {
      std::printf("no support path: %s (%ld expansions)\n", sp.message().c_str(), sp.expansions());
      return kExitTimeLimit;
    }
    std::printf("support path: sticking forces within %.2f of the friction cone, %ld expansions\n",
                sp.frictionUse(), sp.expansions());
  } else {
    found = rp.solve(problem, plan);
    if (tty) std::fprintf(stderr, "\n");
    if (InterruptFlag::raised()) {
      if (found) outputs.write(model, plan);
      std::printf("interrupted: best distance %.3g (tolerance units)%s; %llu propagations\n",
                  rp.bestDistance(), found && outputs.any() ? ", best plan so far written" : "",
                  static_cast<unsigned long long>(rp.propagations()));
      return kExitInterrupted;
    }
  }
  auto stage = [&](const char* what) {
    if (tty) std::fprintf(stderr, "plan-reorientation: %s\n", what);
  };
  certificate.trial.position_tolerance = settings.position_tolerance;
  certificate.trial.angle_tolerance = settings.angle_tolerance;
  if (found && plan.status == "exact") {
    std::printf(
        "exact plan: %zu segments, %.3f s of motion, phases %s; planned in %.3f s, %llu "
        "propagations\n",
        plan.segments.size(), plan.duration(), plan.phaseSequence().c_str(), plan.planning_time,
        static_cast<unsigned long long>(plan.propagations));
    if (support) {
      std::printf("optimisation: not run (support plans are not refined yet)\n");
    }
    if (!o.no_optimize && !support) {
      stage("optimising, then certifying the planner's and the optimised plans");
      trajopt::RefineOutcome refined = trajopt::refinePlan(optimizer, plan, refine);
      if (InterruptFlag::raised()) {  // stopped: the planner's plan, not certified
        plan.certificate = {};
        outputs.write(model, plan);
        std::printf("interrupted during the optimisation: planner's plan%s, not certified\n",
                    outputs.any() ? " written" : "");
        return kExitInterrupted;
      }
      printOptimisation(refined);
      plan = std::move(refined.plan);
    } else {
      stage("certifying the plan");
      plan.certificate = planner::certify(model, plan, certificate, nullptr, settings.cancel);
      if (InterruptFlag::raised()) {
        plan.certificate = {};
        outputs.write(model, plan);
        std::printf("interrupted while certifying: plan%s, not certified\n",
                    outputs.any() ? " written" : "");
        return kExitInterrupted;
      }
    }
    printCertificate(plan.certificate);
    outputs.write(model, plan);
    if (plan.certificate.certified) return 0;
    std::fprintf(stderr, "plan-reorientation: the plan written is %s\n",
                 planner::verdictText(plan.certificate).c_str());
    return kExitNotCertified;
  }
  if (found) {
    stage("certifying the approximate plan");
    plan.certificate = planner::certify(model, plan, certificate, nullptr, settings.cancel);
    if (InterruptFlag::raised()) plan.certificate = {};
    if (plan.certificate.ran) printCertificate(plan.certificate);
    outputs.write(model, plan);
  }
  if (support) {
    // The path was found; its closed-loop run missed the goal (the part left the supports).
    if (plan.samples.empty() || !plan.samples.back().q.allFinite()) {
      std::printf("no exact plan: the support path's closed-loop run lost the part%s\n",
                  outputs.any() ? ", approximate plan written" : "");
      return kExitTimeLimit;
    }
    const planner::PlanSample& end = plan.samples.back();
    std::printf(
        "no exact plan: the support path's closed-loop run %sends %.3g m and %.3g deg from "
        "the goal%s\n",
        end.f_n.maxCoeff() > 0.0 ? "" : "drops the part: it ",
        std::hypot(end.q[layout::kX] - problem.goal.x, end.q[layout::kY] - problem.goal.y),
        std::abs(planner::goalAngleError(end.q[layout::kPhi], problem.goal.phi,
                                         problem.absolute_angle)) *
            180.0 / M_PI,
        outputs.any() ? ", approximate plan written" : "");
    return kExitTimeLimit;
  }
  std::printf(
      "no exact plan within %.3g s: best distance %.3g (tolerance units: 1 = 1 cm or "
      "2 deg)%s; %llu propagations\n",
      settings.time_limit, rp.bestDistance(),
      found && outputs.any() ? ", approximate plan written" : "",
      static_cast<unsigned long long>(rp.propagations()));
  return kExitTimeLimit;
}

}  // namespace
}  // namespace rbsf::tools

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("plan-reorientation", argc, argv, rbsf::tools::run);
}
