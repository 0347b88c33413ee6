// plan-reorientation: torques tau(t) that take the part from where it rests to a goal pose
// (kinodynamic search on OMPL with the hybrid contact simulator as propagator).
//
// Exit status: 0 exact solution; 3 time limit without one (best distance printed);
// 2 bad input (option, value, cell, a start the fingers cannot hold, a goal no finger
// reaches); 130 stopped by SIGINT (best plan so far written); 1 internal error.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "plan_outputs.h"
#include "rbsf/dynamics/errors.h"
#include "rbsf/planner/reorientation_planner.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/interrupt.h"
#include "rbsf/tools/tool_main.h"

namespace rbsf::tools {
namespace {

constexpr int kExitTimeLimit = 3;

struct Options {
  std::string cell, start, goal, start_theta = "0", planner = "KPIECE1", time_limit = "30",
                                 seed = "1", out, csv, svg, report, svg_still = "0";
  bool quiet = false, reproducible = false;
};

int run(int argc, char** argv) {
  CLI::App app{
      "Plan a reorientation of the part: tau segments that take it from rest on the "
      "fingers (placed at --start-theta) to the goal pose within 1 cm and 2 degrees. "
      "Poses: COM x,y [m] and angle (radians, or degrees with a deg suffix).",
      "plan-reorientation"};
  app.footer(
      "Exit status: 0 exact solution; 3 time limit without one (best distance printed); 2 bad "
      "input (option, value, file, a start the fingers cannot hold, a goal no finger "
      "reaches), with one message on stderr; 130 stopped by SIGINT (Ctrl-C: the best plan so far "
      "is written; a second Ctrl-C exits at once, writing nothing); 1 internal error.");
  Options o;
  app.add_option("--cell", o.cell, "cell YAML file")->required();
  app.add_option("--start", o.start, "start pose x,y,phi (part at rest)")->required();
  app.add_option("--goal", o.goal, "goal pose x,y,phi")->required();
  app.add_option("--start-theta", o.start_theta, "base angle at the start (default 0)");
  app.add_option("--planner", o.planner, "KPIECE1 (default), RRT, SST, EST or PDST");
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
  parseCommandLine(app, argc, argv);
  const PlanOutputs outputs({o.out, o.csv, o.svg, o.report, o.reproducible,
                             parseNumber(o.svg_still, "--svg-still"), o.cell});

  planner::PlannerSettings settings;
  settings.planner = o.planner;
  settings.time_limit = parseNumber(o.time_limit, "--time-limit");
  if (settings.time_limit <= 0.0) throw InputError("--time-limit: must be positive");
  const double seed = parseNumber(o.seed, "--seed");
  if (seed < 1 || seed > 4294967295.0 || seed != std::floor(seed))
    throw InputError("--seed: must be an integer in 1..4294967295 (got " + o.seed + ")");
  settings.seed = static_cast<std::uint32_t>(seed);
  planner::Problem problem;
  problem.start = parsePose(o.start, "--start");
  problem.goal = parsePose(o.goal, "--goal");
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
  planner::ReorientationPlanner rp(model, settings);
  rp.checkProblem(problem);  // bad input before any search
  planner::Plan plan;
  const bool found = rp.solve(problem, plan);
  if (tty) std::fprintf(stderr, "\n");
  if (found) outputs.write(model, plan);
  if (InterruptFlag::raised()) {
    std::printf("interrupted: best distance %.3g (tolerance units)%s; %llu propagations\n",
                rp.bestDistance(), found && outputs.any() ? ", best plan so far written" : "",
                static_cast<unsigned long long>(rp.propagations()));
    return kExitInterrupted;
  }
  if (found && plan.status == "exact") {
    std::printf(
        "exact plan: %zu segments, %.3f s of motion, phases %s; planned in %.3f s, %llu "
        "propagations\n",
        plan.segments.size(), plan.duration(), plan.phaseSequence().c_str(), plan.planning_time,
        static_cast<unsigned long long>(plan.propagations));
    return 0;
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
