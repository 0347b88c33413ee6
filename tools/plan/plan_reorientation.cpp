// plan-reorientation: torques tau(t) that take the part from where it rests to a goal pose.
// Plan, refine and certify until a plan certifies or the time limit is spent
// (rbsf/planner/pipeline/reorientation_pipeline.h): the support planner, then the kinodynamic
// planner seed after seed; each exact kinodynamic plan refined by the trajectory optimiser
// unless --no-optimize (rbsf/trajopt/plan_refinement.h); every plan run closed loop under
// the cell's sensing and uncertainty and judged by the lower confidence bound of its
// success rate (rbsf/plan/certificate.h). The first certified plan is written, else the
// best one, marked not certified.
//
// Exit status: 0 a certified plan written; 4 an exact plan written but not certified
// (verdict and worst trial on stderr); 3 time limit without an exact plan (where the
// closest plan ends, in metres and degrees; the approximate plan, certified, written), or
// every search ended without a path (nothing written); 2 bad input (option, value, file, a
// start the fingers cannot hold, a goal no finger reaches); 130 stopped by SIGINT, 143 by
// SIGTERM (best plan so far written, not certified); 1 internal error.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "plan_outputs.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/planner/pipeline/reorientation_pipeline.h"
#include "rbsf/tools/certificate_options.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/interrupt.h"
#include "rbsf/tools/tool_main.h"

namespace rbsf::tools {
namespace {

constexpr int kExitTimeLimit = 3;
constexpr int kExitNotCertified = 4;

struct Options {
  std::string cell, start, goal,
      start_theta = "0", planner = "auto", attempts = "0", time_limit = "30", seed = "1", out, csv,
      svg, report, svg_still = "0", knots = "100", optimize_time_limit = "30",
      optimize_iterations = "500", optimize_tolerance = "1e-6", goal_angle = "nearest",
      trial_seed = "1", friction_use, simple_turns, support_lattice, max_expansions,
      max_propagations;
  CertificateOptions certificate;
  bool quiet = false, no_optimize = false, reproducible = false, no_decisive_modes = false;
};

/// The support planner's defaults as the options write them: "0.45,0.6" and "5deg,0.02".
std::string defaultFrictionUses() {
  std::string out;
  for (double use : planner::SupportPlannerSettings{}.friction_uses)
    out += (out.empty() ? "" : ",") + numberText(use);
  return out;
}
std::string defaultLattice() {
  const planner::SupportSearchSettings s = planner::SupportPlannerSettings::defaultSearch();
  return numberText(s.angle_step * 180.0 / M_PI) + "deg," + numberText(s.xy_step);
}

/// A list of friction uses, each in (0, 1].
std::vector<double> parseFrictionUses(const std::string& text, const std::string& key) {
  const std::vector<double> uses = parseList(text, key);
  for (double use : uses)
    if (!(use > 0.0 && use <= 1.0))
      throw InputError(key + ": each share of the friction cone must be in (0, 1] (got " +
                       numberText(use) + ")");
  return uses;
}

/// --friction-use, --simple-turns and --support-lattice, when given, into the support
/// planner's settings. The lattice's expansion cap grows with the number of its cells
/// (angle^2 x position).
void parseSupportOptions(const std::string& friction_use, const std::string& simple_turns,
                         const std::string& lattice, planner::SupportPlannerSettings& support) {
  if (!friction_use.empty())
    support.friction_uses = parseFrictionUses(friction_use, "--friction-use");
  if (!simple_turns.empty())
    support.simple_turn_friction_uses = parseFrictionUses(simple_turns, "--simple-turns");
  if (lattice.empty()) return;
  const std::vector<std::string_view> steps =
      parseFields(lattice, "--support-lattice", 2, "angle,position");
  const double angle = parseAngle(steps[0], "--support-lattice entry 1 (angle)");
  const double position = parseNumber(steps[1], "--support-lattice entry 2 (position)");
  if (!(angle >= 0.5 * M_PI / 180 && angle <= 45.0 * M_PI / 180))
    throw InputError("--support-lattice: the angle step must be in 0.5deg..45deg (got " +
                     std::string(steps[0]) + ")");
  if (!(position >= 0.001 && position <= 0.2))
    throw InputError("--support-lattice: the position step must be in 0.001..0.2 m (got " +
                     std::string(steps[1]) + ")");
  planner::SupportSearchSettings& search = support.search;
  const double cells = std::pow(search.angle_step / angle, 2) * (search.xy_step / position);
  search.max_expansions =
      static_cast<long>(std::min(1e9, std::max(1.0, cells) * search.max_expansions));
  search.angle_step = angle;
  search.xy_step = position;
  search.goal_theta_step = std::min(search.goal_theta_step, angle);
}

/// The optimiser's line: which solve, how it went, and whether its plan was chosen.
void printOptimisation(const planner::RefinementResult& r) {
  const plan::OptimizationSummary& o = r.record.optimization;
  const char* which = r.solves < 2 ? "" : (r.refined ? " (the retry)" : " (first of 2 solves)");
  std::printf("optimisation%s: %s, %d iterations, %.3f s, cost %.6g -> %.6g\n", which,
              plan::toString(o.status), o.iterations, o.solve_time, o.cost_before, o.cost_after);
  std::printf("planner's plan: %s\n", plan::verdictText(r.planner_certificate).c_str());
  if (o.refined_success_rate >= 0.0)
    std::printf("optimised plan: %.0f %% of the trials succeeded\n",
                100.0 * o.refined_success_rate);
  if (r.refined)
    std::printf(
        "written: the optimised plan (its certificate's lower bound %.3f is at least the "
        "planner's plan's %.3f; effort %.2f of the planner's)\n",
        r.record.certificate.lower_bound, r.planner_certificate.lower_bound,
        o.cost_before > 0.0 ? o.cost_after / o.cost_before : 1.0);
  else
    std::printf("written: the planner's plan%s\n",
                o.message.empty() ? "" : (" (" + o.message + ")").c_str());
}

/// Where a plan leaves the part: "ends 0.123 m and 35.2 deg from the goal" (with "drops the
/// part: it " before it when no contact carries the part at the end).
std::string endText(const plan::Plan& plan, const planner::Problem& problem) {
  if (plan.samples.empty() || !plan.samples.back().q.allFinite()) return "loses the part";
  const plan::PlanSample& end = plan.samples.back();
  return std::string(end.f_n.maxCoeff() > 0.0 ? "" : "drops the part: it ") + "ends " +
         goalDistanceText(end.q, problem.goal, problem.absolute_angle);
}

/// The certificate of the plan written: verdict, law and worst trial, in metres and degrees.
void printCertificate(const plan::Certificate& c) {
  std::fputs(plan::certificateReportText(c).c_str(), stdout);
}

/// The problem and the search's options.
void addSearchOptions(CLI::App& app, Options& o) {
  app.add_option("--cell", o.cell, "cell YAML file")->required();
  app.add_option("--start", o.start, "start pose x,y,phi (part at rest)")->required();
  app.add_option("--goal", o.goal, "goal pose x,y,phi")->required();
  app.add_option("--goal-angle", o.goal_angle,
                 "nearest (default): the goal angle modulo 360 deg, reached whichever way is "
                 "shorter; absolute: the part's total turn from phi = 0, so -270deg asks for "
                 "three quarters of a clockwise turn");
  app.add_option("--start-theta", o.start_theta, "base angle at the start (default 0)");
  app.add_option("--planner", o.planner,
                 "auto (default): the support planner, then KPIECE1 with seeds --seed, "
                 "--seed + 1, ... until a plan certifies; support: slow quasi-static supports "
                 "held by the joints only; KPIECE1, RRT, SST, EST or PDST: that kinodynamic "
                 "planner only, seed after seed");
  app.add_option("--time-limit", o.time_limit,
                 "search budget of every attempt together, seconds (default 30; auto gives "
                 "the support planner half)");
  app.add_option("--seed", o.seed, "first kinodynamic seed, positive integer (default 1)");
  app.add_option("--attempts", o.attempts,
                 "kinodynamic searches at most (default 0: while the time limit lasts)");
}

/// The output files' options.
void addOutputOptions(CLI::App& app, Options& o) {
  app.add_option("--out", o.out, "write the plan as JSON");
  app.add_option("--csv", o.csv, "write the sampled trajectory as CSV");
  app.add_option("--svg", o.svg, "write an animated SVG of the plan");
  app.add_option("--report", o.report, "write an HTML page: animation and plots over time");
  app.add_option("--svg-still", o.svg_still, "time [s] of the frame non-animating viewers show");
  app.add_flag("--reproducible", o.reproducible,
               "leave wall-clock fields (planning_time) out of the files: the same seed gives "
               "byte-identical files");
  app.add_flag("--quiet", o.quiet,
               "no progress on stderr (else: a line per stage, and on a terminal a line "
               "redrawn every second, elsewhere a line every 5 s of a search)");
  app.add_flag("--no-decisive-modes", o.no_decisive_modes,
               "let contacts change mode anywhere within a held torque (plans a tracking cell "
               "often cannot repeat; see docs/tools.md)");
  app.add_flag("--no-optimize", o.no_optimize, "write the planner's plan without optimising it");
}

/// The optimiser's, the certificate's and the support planner's options.
void addStageOptions(CLI::App& app, Options& o) {
  app.add_option("--knots", o.knots, "collocation intervals of the optimiser (default 100)");
  app.add_option("--optimize-time-limit", o.optimize_time_limit,
                 "optimiser wall-time limit per solve in seconds (default 30)");
  app.add_option("--optimize-iterations", o.optimize_iterations,
                 "optimiser iteration limit (default 500)");
  app.add_option("--optimize-tolerance", o.optimize_tolerance,
                 "optimiser convergence tolerance, Ipopt's tol in (0, 1] (default 1e-6; 1e-4 "
                 "takes about a quarter fewer iterations, see docs/optimiser.md)");
  o.certificate.addTo(app);
  app.add_option("--trial-seed", o.trial_seed,
                 "seed of the certificate's draws, positive integer (default 1)");
  app.add_option("--friction-use", o.friction_use,
                 "support planner: the sticking forces' share of the friction cone, one search "
                 "per value in order, each in (0, 1] (default " +
                     defaultFrictionUses() + ")");
  app.add_option("--simple-turns", o.simple_turns,
                 "support planner: first search simple turns (pivot_turn_search.h: the fewest "
                 "pivots, at most 3, each with one sliding tip) at these friction uses, each in "
                 "(0, 1] (default: none; 0.6 certifies the default cell's +5, -15 and -20 "
                 "degree turns)");
  app.add_option("--max-expansions", o.max_expansions,
                 "support planner: at most this many expansions over all its searches, a "
                 "budget that gives the same plan on any machine where the time limit does not "
                 "bind first (default: none)");
  app.add_option("--max-propagations", o.max_propagations,
                 "kinodynamic planner: at most this many propagations per search, a budget that "
                 "gives the same plan on any machine where the time limit does not bind first "
                 "(default: none)");
  app.add_option("--support-lattice", o.support_lattice,
                 "support planner: the search's angle and position steps (default " +
                     defaultLattice() + "; finer lattices find more paths and take longer)");
}

/// The pipeline's settings from the options. \throws InputError naming a bad option.
planner::PipelineSettings pipelineSettings(const Options& o) {
  const std::optional<planner::KinodynamicPlanner> kinodynamic = planner::parsePlanner(o.planner);
  if (o.planner != "auto" && o.planner != "support" && !kinodynamic)
    throw InputError("--planner: unknown planner '" + o.planner +
                     "' (choose from auto, support, KPIECE1, RRT, SST, EST, PDST)");
  using Method = planner::PipelineMethod;
  planner::PipelineSettings pipeline;
  pipeline.method = o.planner == "auto"      ? Method::kAuto
                    : o.planner == "support" ? Method::kSupport
                                             : Method::kKinodynamic;
  planner::PlannerSettings& settings = pipeline.planner;
  settings.planner = kinodynamic.value_or(planner::KinodynamicPlanner::kKPIECE1);
  settings.decisive_modes.enabled = !o.no_decisive_modes;
  settings.time_limit = parseNumber(o.time_limit, "--time-limit");
  if (!(settings.time_limit > 0.0 && settings.time_limit <= 1e6))
    throw InputError("--time-limit: must be positive, at most 1e6 s (got " + o.time_limit + ")");
  settings.seed = static_cast<std::uint32_t>(parseInteger(o.seed, "--seed", 1, 4294967295LL));
  pipeline.max_attempts = static_cast<int>(parseInteger(o.attempts, "--attempts", 0, 1000000));
  pipeline.optimize = !o.no_optimize;
  trajopt::OptimizerSettings& opt = pipeline.optimizer;
  opt.knots = static_cast<int>(parseInteger(o.knots, "--knots", 2, 100000));
  opt.max_solve_time = parseNumber(o.optimize_time_limit, "--optimize-time-limit");
  if (!(opt.max_solve_time > 0.0))
    throw InputError("--optimize-time-limit: must be positive (got " + o.optimize_time_limit + ")");
  opt.max_iterations =
      static_cast<int>(parseInteger(o.optimize_iterations, "--optimize-iterations", 1, 1000000));
  opt.tolerance = parseNumber(o.optimize_tolerance, "--optimize-tolerance");
  if (!(opt.tolerance > 0.0 && opt.tolerance <= 1.0))
    throw InputError("--optimize-tolerance: must be in (0, 1] (got " + o.optimize_tolerance + ")");
  o.certificate.apply(pipeline.certificate);
  pipeline.certificate.seed =
      static_cast<std::uint64_t>(parseInteger(o.trial_seed, "--trial-seed", 1, 1LL << 53));
  parseSupportOptions(o.friction_use, o.simple_turns, o.support_lattice, pipeline.support);
  if (!o.max_expansions.empty())
    pipeline.support.max_expansions =
        parseInteger(o.max_expansions, "--max-expansions", 1, 1000000000);
  if (!o.max_propagations.empty())
    settings.max_propagations = static_cast<std::uint64_t>(
        parseInteger(o.max_propagations, "--max-propagations", 1, 1000000000000LL));
  return pipeline;
}

/// The problem from the options. \throws InputError naming a bad option.
planner::Problem problemOf(const Options& o) {
  planner::Problem problem;
  problem.start = parsePose(o.start, "--start");
  problem.goal = parsePose(o.goal, "--goal");
  if (o.goal_angle != "nearest" && o.goal_angle != "absolute")
    throw InputError("--goal-angle: must be nearest or absolute (got " + o.goal_angle + ")");
  problem.absolute_angle = o.goal_angle == "absolute";
  problem.start_theta = parseAngle(o.start_theta, "--start-theta");
  return problem;
}

/// The pipeline's events as lines: progress and stages on stderr (unless --quiet: on a
/// terminal one line redrawn every second; else, a log or a pipe, a line per stage and one
/// every 5 s of a search), plans found, refinements and verdicts on stdout.
class EventPrinter {
 public:
  explicit EventPrinter(bool quiet) : quiet_(quiet), tty_(isatty(fileno(stderr)) != 0) {}

  void operator()(const planner::StageStarted& e) {
    if (quiet_) return;
    std::fprintf(stderr, "%splan-reorientation: %s\n", progress_shown_ ? "\n" : "",
                 planner::stageText(e.stage, e.attempt.method(), e.attempt.seed).c_str());
    progress_shown_ = false;
    last_line_ = -1e9;
  }
  void operator()(const planner::SearchProgress& e) {
    const planner::Progress& p = e.progress;
    if (quiet_ || (!tty_ && p.elapsed < last_line_ + 5.0)) return;
    if (!tty_) last_line_ = p.elapsed;
    std::fprintf(
        stderr,
        "%splan-reorientation: %6.1f s  %10llu propagations  closest %.3g (1 = 1 cm or 2 deg)%s",
        tty_ ? "\r" : "", p.elapsed, static_cast<unsigned long long>(p.propagations),
        p.best_distance, tty_ ? " " : "\n");
    std::fflush(stderr);
    progress_shown_ = tty_;
  }
  void operator()(const planner::PlanFound& e) const {
    const planner::PipelineAttempt& a = e.attempt;
    if (a.search == planner::SearchKind::kSupport) {
      std::printf("support path: sticking forces within %.2f of the friction cone, %ld expansions",
                  a.friction_use, a.expansions);
      if (a.paths_run > 1)
        std::printf(
            ", %d paths run closed loop (kept: the first whose run ends on the goal, else the "
            "one that followed its reference longest)",
            a.paths_run);
      std::printf("\n");
    }
    const plan::Plan& plan = e.plan;
    if (plan.status != plan::PlanStatus::kExact) return;
    std::printf(
        "exact plan: %zu segments, %.3f s of motion, %d pivot%s (planned phases %s), phases %s; "
        "planned in %.3f s, %llu propagations\n",
        plan.segments.size(), plan.duration(), plan.pivots(), plan.pivots() == 1 ? "" : "s",
        plan.plannedPhases().c_str(), plan.phaseSequence().c_str(), plan.planning_time,
        static_cast<unsigned long long>(plan.propagations));
  }
  void operator()(const planner::PlanRefined& e) const {
    if (!InterruptFlag::raised()) printOptimisation(e.refinement);
  }
  void operator()(const planner::AttemptJudged& e) const {
    const planner::PipelineAttempt& a = e.attempt;
    if (!a.found && a.search == planner::SearchKind::kSupport)
      std::printf("no support path: %s (%ld expansions)\n", a.note.c_str(), a.expansions);
    else if (!a.found)
      std::printf("%s, seed %u: no path within the time left\n", a.method().c_str(), a.seed);
    else if (a.certificate.ran)
      printCertificate(a.certificate);
  }

 private:
  bool quiet_, tty_;
  bool progress_shown_ = false;
  double last_line_ = -1e9;
};

/// A support search that found nothing answers what the cell allows: what it reached and
/// the rule that refused the moves beyond (stderr, and a section of the report).
std::vector<ReportSection> reachSections(const planner::PipelineOutcome& result) {
  std::vector<ReportSection> sections;
  for (const planner::PipelineAttempt& a : result.attempts)
    if (a.search == planner::SearchKind::kSupport && !a.found && a.reach.measured && !a.cancelled) {
      const std::string reach = a.reach.text();
      std::fprintf(stderr, "plan-reorientation: no support path; the search %s\n", reach.c_str());
      sections.push_back(
          {"reach", "What the support planner reached",
           "The support search found no path (" + a.note + "). It " + reach +
               ". The rule that refused most of the moves beyond the closest pose: " +
               planner::supportRuleText(a.reach.stoppedBy()) + "."});
    }
  return sections;
}

/// Write what the run produced and say what it is; returns the exit status (file comment).
int report(const planner::PipelineOutcome& result, const planner::PipelineSettings& pipeline,
           const planner::Problem& problem, const RbsfModel& model, const PlanOutputs& outputs) {
  const plan::PlanRecord& record = result.record;
  const plan::Plan& plan = record.plan;
  const planner::PipelineAttempt* chosen = result.chosenAttempt();
  const bool support = chosen != nullptr && chosen->search == planner::SearchKind::kSupport;
  const std::vector<ReportSection> sections = reachSections(result);
  if (chosen != nullptr && result.attempts.size() > 1)
    std::printf("chosen: attempt %d of %zu (%s%s), %s\n", result.chosen + 1, result.attempts.size(),
                chosen->method().c_str(),
                support ? "" : (", seed " + std::to_string(chosen->seed)).c_str(),
                planner::statusText(result.status));
  const double time_limit = pipeline.planner.time_limit;
  switch (result.status) {
    case planner::PipelineStatus::kCancelled:
      if (chosen != nullptr) {
        outputs.write(model, record, sections);
        std::printf("interrupted: the best plan so far %s%s, not certified\n",
                    endText(plan, problem).c_str(), outputs.any() ? ", written" : "");
      } else {
        std::printf("interrupted: no plan yet, nothing written\n");
      }
      return InterruptFlag::exitStatus();
    case planner::PipelineStatus::kCertified:
      outputs.write(model, record, sections);
      return 0;
    case planner::PipelineStatus::kNotCertified:
      outputs.write(model, record, sections);
      std::fprintf(stderr, "plan-reorientation: the plan written is %s\n",
                   plan::verdictText(record.certificate).c_str());
      return kExitNotCertified;
    case planner::PipelineStatus::kNoPlan:
      // A search that ran out of nodes is an answer, not a time limit: say which it was.
      if (result.wall_time < 0.99 * time_limit)
        std::printf("no plan: every search ended without a path, after %.3g s of %.3g\n",
                    result.wall_time, time_limit);
      else
        std::printf("no plan within %.3g s\n", time_limit);
      return kExitTimeLimit;
    case planner::PipelineStatus::kApproximate:
      break;
  }
  outputs.write(model, record, sections);
  // The support path was found but its closed-loop run missed the goal; a kinodynamic
  // search ended at its closest approach. What ended the search: the time limit, the
  // budget, or (support) the paths it had.
  char within[64] = "";
  if (result.wall_time >= 0.99 * time_limit)
    std::snprintf(within, sizeof within, " within %.3g s", time_limit);
  else if (!support && pipeline.planner.max_propagations > 0)
    std::snprintf(within, sizeof within, " within %llu propagations",
                  static_cast<unsigned long long>(pipeline.planner.max_propagations));
  std::printf("no exact plan%s: the %s %s%s\n", within,
              support ? "support path's closed-loop run" : "closest plan",
              endText(plan, problem).c_str(), outputs.any() ? ", approximate plan written" : "");
  return kExitTimeLimit;
}

int run(int argc, char** argv) {
  CLI::App app{
      "Plan a reorientation of the part: tau segments that take it from rest on the "
      "fingers (placed at --start-theta) to the goal pose within 1 cm and 2 degrees. "
      "Poses: COM x,y [m] and angle (radians, or degrees with a deg suffix).",
      "plan-reorientation"};
  app.footer(
      "Every plan written is certified: replayed in closed loop under the cell's sensing and "
      "uncertainty (cell keys sensing and uncertainty) and judged by outcome: the part ends "
      "at rest within 1 cm and 2 degrees of the goal, never dropped, inputs within their "
      "limits, the plan within the cell's motion limits; certified when the one-sided 95 % "
      "Clopper-Pearson lower bound of the success rate is at least 0.95 (--confidence, "
      "--required-rate), the trials run in batches of 64 until the bound decides, at most 512 "
      "(--trial-batch, --max-trials), or exactly --trials N. Planning goes on until a plan "
      "certifies: the support "
      "planner, then kinodynamic seeds while --time-limit lasts; exact kinodynamic plans are "
      "refined by the trajectory optimiser (unless --no-optimize). The first certified plan "
      "is written, else the best one found, marked not certified.\n"
      "Exit status: 0 a certified plan written; 4 an exact plan written but not certified "
      "(verdict on stderr); 3 time limit without an exact plan (where the closest plan ends, "
      "in metres and degrees; the approximate plan written), or every search ended without a "
      "path (nothing written); 2 bad input (option, value, "
      "file, a start the fingers cannot hold, a goal no finger reaches), with one message on "
      "stderr; 130 stopped by SIGINT, 143 by SIGTERM (Ctrl-C or kill, during the search or "
      "the optimisation: the best plan so far is written, not certified; a second signal "
      "exits at once, writing nothing); 1 internal error.");
  Options o;
  addSearchOptions(app, o);
  addOutputOptions(app, o);
  addStageOptions(app, o);
  parseCommandLine(app, argc, argv);
  const PlanOutputs outputs({o.out, o.csv, o.svg, o.report, o.reproducible,
                             parseNumber(o.svg_still, "--svg-still"), o.cell});
  const planner::PipelineSettings pipeline = pipelineSettings(o);
  const planner::Problem problem = problemOf(o);
  const RbsfModel model(loadCell(o.cell));
  planner::ReorientationPipeline run(model, pipeline);  // bad settings: exit 2
  planner::RunContext context;
  context.cancel = &InterruptFlag::install();  // Ctrl-C: stop and write the best so far
  EventPrinter printer(o.quiet);
  context.on_event = [&printer](const planner::PipelineEvent& e) { std::visit(printer, e); };
  // A bad problem: exit 2 before any search.
  const planner::PipelineOutcome result = run.run(problem, context);
  return report(result, pipeline, problem, model, outputs);
}

}  // namespace
}  // namespace rbsf::tools

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("plan-reorientation", argc, argv, rbsf::tools::run);
}
