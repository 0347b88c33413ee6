// rbsf-controller-loop: a cell controller's 1 kHz loop around the library's facade
// (rbsf/controller/reorientation_controller.h), with the hybrid simulator as the plant and
// the cell's sensors simulated (rbsf/dynamics/control/sensor_model.h: noisy joints every tick, the
// part's pose at the sensor's rate, late by its latency).
//
//   With --plan FILE the plan file is loaded instead (checked against the cell: a plan made
//   for another cell is bad input, exit 2) and executed from step 2.
//   1. The part rests on the fingers at --start; while the worker thread plans and
//      certifies, the loop holds it with the library's hold plan (planner::holdPlan: the
//      contact set that holds it best, the other fingers lifted; a hold is a plan like any
//      other) run by an executor. The loop never waits for the planner.
//   2. When a plan is published, the loop executes it: each period (the plan's time step)
//      the joints go to track(t, joints, tau, status) and each part pose to
//      addPartPose(stamp, pose); the plant steps one period. Each change of the execution
//      status's verdict is printed (at most 20), with what the status found.
//   3. After the plan's end the law holds the final pose at rest for --settle seconds.
// The facade publishes only certified plans unless --accept-uncertified. The loop is paced
// by the wall clock (one tick per millisecond) unless --no-pace.
//
// Exit status: 0 the plan was executed (the final pose error and the loop's timing are
// printed); 4 the plan failed its certificate and was not run (verdict on stderr); 3
// planning failed otherwise (no path, time limit, cancelled); 2 bad input (an option, the
// cell, a start the fingers cannot hold, a goal no finger reaches); 1 internal error.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>

#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/control/plan_executor.h"
#include "rbsf/dynamics/control/sensor_model.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/plan/plan_fit.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/planner/support/hold_plan.h"
#include "rbsf/tools/certificate_options.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/tool_main.h"

namespace rbsf::tools {
namespace {

using Clock = std::chrono::steady_clock;

/// \brief Wall-clock pacing of the loop and its timing statistics.
class Pacer {
 public:
  explicit Pacer(bool pace) : pace_(pace), next_(Clock::now()) {}
  void tickStart() {
    start_ = Clock::now();
    if (pace_) late_ = std::max(late_, std::chrono::duration<double>(start_ - next_).count());
  }
  /// \brief End of a tick's work: record its cost, then sleep until the next tick.
  void tickEnd() {
    const auto end = Clock::now();
    worst_ = std::max(worst_, std::chrono::duration<double>(end - start_).count());
    next_ += std::chrono::milliseconds(1);
    if (!pace_) return;
    if (end > next_) ++overruns_;
    std::this_thread::sleep_until(next_);
  }
  double worst() const { return worst_; }
  long overruns() const { return overruns_; }
  double worstLateStart() const { return late_; }

 private:
  bool pace_;
  Clock::time_point next_, start_;
  double worst_ = 0.0, late_ = 0.0;
  long overruns_ = 0;
};

int run(int argc, char** argv) {
  CLI::App app{
      "Simulated 1 kHz cell-controller loop: hold the part while the facade plans and "
      "certifies on its worker thread, then execute the plan with the control law on "
      "simulated sensors; prints the final pose error and the loop's timing.",
      "rbsf-controller-loop"};
  app.footer(
      "Exit status: 0 plan executed; 4 the plan failed its certificate (not run); 3 planning "
      "failed; 2 bad input; 1 internal error.");
  std::string cell, start_text, goal_text, theta_text = "0", limit_text = "30", seed_text = "1",
                                           settle_text = "1";
  bool no_pace = false, optimize = false, accept_uncertified = false;
  std::string plan_file;
  app.add_option("--cell", cell, "cell YAML file")->required();
  app.add_option("--plan", plan_file,
                 "run this plan file (plan-reorientation --out) instead of planning; refused "
                 "(exit 2) when it was made for another cell");
  app.add_option("--start", start_text, "start pose x,y,phi (part at rest; not with --plan)");
  app.add_option("--goal", goal_text, "goal pose x,y,phi (not with --plan)");
  app.add_option("--start-theta", theta_text, "base angle at the start (default 0)");
  app.add_option("--time-limit", limit_text, "planning time limit [s] (default 30)");
  app.add_option("--seed", seed_text, "planner seed (default 1)");
  app.add_option("--settle", settle_text, "holding the final pose after the plan [s] (default 1)");
  CertificateOptions certificate;
  certificate.addTo(app);
  app.add_flag("--accept-uncertified", accept_uncertified,
               "execute a plan that failed its certificate (a cell should not)");
  app.add_flag("--optimize", optimize, "refine the plan with rbsf::trajopt");
  std::string knots_text = "100";
  app.add_option("--knots", knots_text, "optimiser collocation intervals (default 100)");
  app.add_flag("--no-pace", no_pace, "run the loop as fast as possible");
  parseCommandLine(app, argc, argv);

  controller::ReorientationRequest request;
  plan::PlanRecord given_record;  // --plan: the plan to run, its start the plant's
  const plan::Plan& given = given_record.plan;
  if (!plan_file.empty()) {
    if (!start_text.empty() || !goal_text.empty())
      throw InputError("--plan: the plan file gives the start and the goal, not --start/--goal");
    given_record = plan::readPlanJson(plan_file);
    request.problem.start = given.start;
    request.problem.goal = given.goal;
    request.problem.start_theta = given.start_theta;
    request.planner.simulator = given.simulator;
  } else {
    if (start_text.empty() || goal_text.empty())
      throw InputError("--start and --goal: required unless --plan gives a plan file");
    request.problem.start = parsePose(start_text, "--start");
    request.problem.goal = parsePose(goal_text, "--goal");
    request.problem.start_theta = parseAngle(theta_text, "--start-theta");
  }
  request.planner.time_limit = parseNumber(limit_text, "--time-limit");
  if (!(request.planner.time_limit > 0.0)) throw InputError("--time-limit: must be positive");
  request.planner.seed =
      static_cast<std::uint32_t>(parseInteger(seed_text, "--seed", 1, 4294967295LL));
  const double settle = parseNumber(settle_text, "--settle");
  if (!(settle >= 0.0 && settle <= 60.0)) throw InputError("--settle: must be in [0, 60] s");
  certificate.apply(request.certificate);
  request.accept_uncertified = accept_uncertified;
  request.optimize = optimize;
  request.optimizer.knots = static_cast<int>(parseInteger(knots_text, "--knots", 2, 2000));

  FeedbackSettings feedback;
  feedback.timing.settle_time = settle;
  controller::ReorientationController ctl(cell, feedback);
  const RbsfModel& model = ctl.model();
  const int m = model.numFingers();
  const double h = request.planner.simulator.time_step;

  // The plant at the start, at rest; its sensors; the hold: the library's hold plan (the
  // contact set that holds the part best, the other fingers lifted) run by an executor.
  const VecQ q0 = restingConfiguration(model, request.problem.start, request.problem.start_theta);
  planner::HoldSettings hold_settings;
  hold_settings.duration = 1.0;
  hold_settings.simulator = request.planner.simulator;
  plan::Plan hold_plan;
  try {
    hold_plan = planner::holdPlan(model, q0, hold_settings);
  } catch (const InputError&) {
    throw InputError("--start: the fingers cannot hold the part at rest");
  }
  const FeedbackSchedule hold(model, plan::makeReference(hold_plan),
                              plan::lawSensing(model.cell().sensing, hold_plan),
                              request.planner.simulator);
  PlanExecutor holder(hold);
  const Simulator plant(model, request.planner.simulator);
  auto ws = std::make_unique<SimulatorWorkspace>(m);
  SimState state(q0, VecQ::Zero(q0.size()));
  SensorModel sensors(model.cell().sensing, h, 1);
  VecU tau(model.controlDim()), joints(model.controlDim());
  ReferenceSample ref;

  Pacer pacer(!no_pace);
  if (!plan_file.empty()) {
    // 1'. A plan file: checked against the cell and published; no planning.
    std::string why;
    if (!ctl.load(given_record, &why, accept_uncertified)) {
      // A plan for this cell that failed its certificate is not run (4), as a planned one;
      // anything else is bad input (2).
      if (!plan::planCellMismatch(model, given).empty() || given_record.certificate.certified)
        throw InputError("--plan " + plan_file + ": " + why);
      std::fprintf(stderr, "rbsf-controller-loop: the plan was not run: %s\n", why.c_str());
      return 4;
    }
    std::printf("loaded     %s\n           %s\n", plan_file.c_str(), ctl.result().message.c_str());
  } else {
    // 1. Hold while the worker plans.
    if (!ctl.plan(request)) throw std::runtime_error("the controller is busy");
    long tick = 0, no_plan_samples = 0;
    double hold_error = 0.0;
    while (ctl.status() == controller::ControllerStatus::kPlanning) {
      pacer.tickStart();
      no_plan_samples += !ctl.sample(0.0, ref);  // nothing published yet: "no plan"
      sensors.joints(state.q, joints);
      sensors.partPose(tick, state.q,
                       [&](double stamp, const Pose& p) { holder.addPartPose(stamp, p); });
      holder.step(static_cast<double>(tick) * h, joints, tau);
      plant.step(state, tau, *ws);
      hold_error = std::max(hold_error, (state.q - q0).head<3>().cwiseAbs().maxCoeff());
      ++tick;
      pacer.tickEnd();
    }
    ctl.wait();
    const controller::RequestResult planned = ctl.result();
    if (planned.outcome == controller::PlanOutcome::kInputError) throw InputError(planned.message);
    std::printf(
        "planning   %s after %.3f s (%ld loop ticks holding the part, which moved at most "
        "%.2e m or rad; %ld samples said \"no plan\")\n",
        controller::toString(planned.outcome), planned.record.plan.planning_time, tick, hold_error,
        no_plan_samples);
    if (!planned.message.empty()) std::printf("           %s\n", planned.message.c_str());
    if (ctl.status() != controller::ControllerStatus::kReady) {
      if (planned.outcome == controller::PlanOutcome::kNotCertified) {
        std::fprintf(stderr, "rbsf-controller-loop: the plan was not run: %s\n",
                     planned.message.c_str());
        return 4;
      }
      std::fprintf(stderr, "rbsf-controller-loop: planning failed (%s): %s\n",
                   controller::toString(planned.outcome), planned.message.c_str());
      return 3;
    }
  }

  // 2. Execute the plan from where the hold left the plant, then hold its end.
  double duration = 0.0;
  VecQ plan_q0;
  ctl.publishedPlan(duration, plan_q0);
  if (ctl.timeStep() != h) throw std::runtime_error("the plan's time step is not the plant's");
  const double start_offset = (state.q - plan_q0).cwiseAbs().maxCoeff();
  const long steps = std::lround((duration + settle) / h);
  double max_error = 0.0;
  ExecutionStatus status;
  ExecutionVerdict shown = ExecutionVerdict::kOnPlan;
  int changes = 0;
  ctl.start();
  for (long k = 0; k < steps; ++k) {
    pacer.tickStart();
    const double t = static_cast<double>(k) * h;
    sensors.joints(state.q, joints);
    sensors.partPose(k, state.q, [&](double stamp, const Pose& p) { ctl.addPartPose(stamp, p); });
    ctl.track(t, joints, tau, status);
    if (status.verdict != shown) {
      if (++changes <= 20)
        std::printf(
            "status     t = %.3f s: %s%s%s (part %.1f mm, %.2f deg off; stroke %.1f mm)%s\n", t,
            toString(status.verdict), status.hold_reason != HoldReason::kNone ? ", held: " : "",
            status.hold_reason != HoldReason::kNone ? toString(status.hold_reason) : "",
            1e3 * status.position_deviation, status.angle_deviation, 1e3 * status.stroke_deviation,
            flagsText(status.flags).c_str());
      shown = status.verdict;
    }
    plant.step(state, tau, *ws);
    ctl.sample(t + h, ref);
    for (int j = 0; j < model.controlDim(); ++j) {
      const int c = layout::inputToConfig(j);
      if (t + h <= duration) max_error = std::max(max_error, std::abs(state.q[c] - ref.q[c]));
    }
    pacer.tickEnd();
  }
  const auto& goal = request.problem.goal;
  const double pos_err = std::hypot(state.q[layout::kX] - goal.x, state.q[layout::kY] - goal.y);
  const double ang_err =
      std::remainder(state.q[layout::kPhi] - goal.phi, 2.0 * M_PI) * 180.0 / M_PI;
  const controller::RequestResult result = ctl.result();
  std::printf("plan       %.3f s, %zu segments, phases %s (%s)\n", duration,
              result.record.plan.segments.size(), result.record.plan.phaseSequence().c_str(),
              controller::toString(result.outcome));
  std::printf("certificate %s\n", plan::verdictText(result.record.certificate).c_str());
  std::printf("status     final: %s after %d change%s of verdict\n", toString(status.verdict),
              changes, changes == 1 ? "" : "s");
  std::printf(
      "executed   max joint error %.3e (rad or m; start offset %.1e); %.2f s after the "
      "end the part is %.4f m and %.3f deg from the goal\n",
      max_error, start_offset, settle, pos_err, ang_err);
  if (no_pace) {
    std::printf("loop       worst tick %.1f us (unpaced)\n", 1e6 * pacer.worst());
  } else {
    std::printf(
        "loop       worst tick %.1f us; %ld ticks ended after their 1 ms deadline, the "
        "latest tick started %.2f ms late\n",
        1e6 * pacer.worst(), pacer.overruns(), 1e3 * pacer.worstLateStart());
  }
  return 0;
}

}  // namespace
}  // namespace rbsf::tools

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf-controller-loop", argc, argv, rbsf::tools::run);
}
