// rbsf-controller-loop: a cell controller's 1 kHz loop around the library's facade
// (rbsf/controller/reorientation_controller.h), with the hybrid simulator as the plant.
//
//   1. The part rests on the fingers at --start; the loop holds it there (the tracking
//      controller around the start at rest with the holding tau as feed-forward) while
//      the worker thread plans the reorientation. The loop never waits for the planner.
//   2. When the plan is published, the loop executes it: computeTorque(t, q, v) each
//      millisecond, the plant steps 1 ms, and the tracking error is recorded.
//   3. After the plan's end it keeps tracking the final reference for --settle seconds
//      (planner plans need not end at rest: the part then moves on).
// The loop is paced by the wall clock (one tick per millisecond) unless --no-pace.
//
// Exit status: 0 the plan was executed (the tracking error and the final pose are
// printed); 3 planning failed (outcome printed); 2 bad input; 1 internal error.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>

#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/holding.h"
#include "rbsf/dynamics/placement.h"
#include "rbsf/dynamics/simulator.h"
#include "rbsf/dynamics/state_layout.h"
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
      "Simulated 1 kHz cell-controller loop: hold the part while the facade plans "
      "on its worker thread, then track the plan; prints the tracking error.",
      "rbsf-controller-loop"};
  app.footer("Exit status: 0 plan executed; 3 planning failed; 2 bad input; 1 internal error.");
  std::string cell, start_text, goal_text, theta_text = "0", limit_text = "30", seed_text = "1",
                                           settle_text = "0";
  bool no_pace = false, optimize = false;
  app.add_option("--cell", cell, "cell YAML file")->required();
  app.add_option("--start", start_text, "start pose x,y,phi (part at rest)")->required();
  app.add_option("--goal", goal_text, "goal pose x,y,phi")->required();
  app.add_option("--start-theta", theta_text, "base angle at the start (default 0)");
  app.add_option("--time-limit", limit_text, "planning time limit [s] (default 30)");
  app.add_option("--seed", seed_text, "planner seed (default 1)");
  app.add_option("--settle", settle_text, "tracking after the plan's end [s] (default 0)");
  app.add_flag("--optimize", optimize, "refine the plan with rbsf::trajopt");
  std::string knots_text = "100";
  app.add_option("--knots", knots_text, "optimiser collocation intervals (default 100)");
  app.add_flag("--no-pace", no_pace, "run the loop as fast as possible");
  parseCommandLine(app, argc, argv);

  controller::ReorientationRequest request;
  request.problem.start = parsePose(start_text, "--start");
  request.problem.goal = parsePose(goal_text, "--goal");
  request.problem.start_theta = parseAngle(theta_text, "--start-theta");
  request.planner.time_limit = parseNumber(limit_text, "--time-limit");
  if (!(request.planner.time_limit > 0.0)) throw InputError("--time-limit: must be positive");
  const double seed = parseNumber(seed_text, "--seed");
  if (seed < 1 || seed > 4294967295.0 || seed != std::floor(seed))
    throw InputError("--seed: must be an integer in 1..4294967295 (got " + seed_text + ")");
  request.planner.seed = static_cast<std::uint32_t>(seed);
  const double settle = parseNumber(settle_text, "--settle");
  if (!(settle >= 0.0 && settle <= 60.0)) throw InputError("--settle: must be in [0, 60] s");
  request.optimize = optimize;
  const double knots = parseNumber(knots_text, "--knots");
  if (!(knots >= 2 && knots <= 2000 && knots == std::floor(knots)))
    throw InputError("--knots: must be an integer in 2..2000 (got " + knots_text + ")");
  request.optimizer.knots = static_cast<int>(knots);

  controller::ReorientationController ctl(cell);
  const RbsfModel& model = ctl.model();
  const int m = model.numFingers();

  // The plant at the start, at rest, and the hold: PD around the start plus holding tau.
  const VecQ q0 = restingConfiguration(model, request.problem.start, request.problem.start_theta);
  ModelData data(m);
  model.updateContacts(q0, data);
  const HoldingSolution holding = holdingTorques(model, q0, data);
  if (!holding.feasible) throw InputError("--start: the fingers cannot hold the part at rest");
  ReferenceSample hold;
  hold.q = q0;
  hold.v = VecQ::Zero(q0.size());
  hold.tau = holding.tau;
  const TrackingController holder(model, q0);
  const Simulator plant(model, request.planner.simulator);
  const double h = request.planner.simulator.time_step;
  auto ws = std::make_unique<SimulatorWorkspace>(m);
  SimState state(q0, VecQ::Zero(q0.size()));
  VecU tau(model.controlDim());
  ReferenceSample ref;

  // 1. Hold while the worker plans.
  Pacer pacer(!no_pace);
  if (!ctl.plan(request)) throw std::runtime_error("the controller is busy");
  long hold_ticks = 0, no_plan_samples = 0;
  double hold_error = 0.0;
  while (ctl.status() == controller::ControllerStatus::kPlanning) {
    pacer.tickStart();
    no_plan_samples += !ctl.sample(0.0, ref);  // nothing published yet: "no plan"
    holder.compute(state.q, state.v, hold, tau);
    plant.step(state, tau, *ws);
    hold_error = std::max(hold_error, TrackingController::jointError(state.q, hold));
    ++hold_ticks;
    pacer.tickEnd();
  }
  ctl.wait();
  const controller::RequestResult result = ctl.result();
  std::printf(
      "planning   %s after %.3f s (%ld loop ticks holding the part, worst joint error "
      "%.2e; %ld samples said \"no plan\")\n",
      controller::toString(result.outcome), result.plan.planning_time, hold_ticks, hold_error,
      no_plan_samples);
  if (!result.message.empty()) std::printf("           %s\n", result.message.c_str());
  if (ctl.status() != controller::ControllerStatus::kReady) return 3;

  // 2. Execute the plan from where the hold left the plant, then settle.
  double duration = 0.0;
  VecQ plan_q0;
  ctl.publishedPlan(duration, plan_q0);
  const double start_offset = (state.q - plan_q0).cwiseAbs().maxCoeff();
  const long steps = std::lround((duration + settle) / h);
  double max_error = 0.0, sum_sq = 0.0;
  VecQ q_end = state.q;  // the plant at the plan's end
  for (long k = 0; k < steps; ++k) {
    pacer.tickStart();
    const double t = k * h;
    ctl.computeTorque(t, state.q, state.v, tau, ref);
    plant.step(state, tau, *ws);
    ctl.sample(t + h, ref);  // the reference at the end of the step
    const double e = TrackingController::jointError(state.q, ref);
    if (t + h <= duration + 0.5 * h) {
      max_error = std::max(max_error, e);
      sum_sq += e * e;
      q_end = state.q;
    }
    pacer.tickEnd();
  }
  const long plan_steps = std::max(1L, std::lround(duration / h));
  const auto& goal = request.problem.goal;
  const auto pos_err = [&](const VecQ& q) {
    return std::hypot(q[layout::kX] - goal.x, q[layout::kY] - goal.y);
  };
  const auto ang_err = [&](const VecQ& q) {
    return std::remainder(q[layout::kPhi] - goal.phi, 2.0 * M_PI) * 180.0 / M_PI;
  };
  const VecQ& q_plan_end = result.plan.samples.back().q;
  std::printf("plan       %.3f s, %zu segments, phases %s (%s)\n", duration,
              result.plan.segments.size(), result.plan.phaseSequence().c_str(),
              controller::toString(result.outcome));
  std::printf("tracking   max joint error %.3e, rms %.3e (rad or m; start offset %.1e)\n",
              max_error, std::sqrt(sum_sq / plan_steps), start_offset);
  std::printf("goal error planned %.4f m %.3f deg; executed %.4f m %.3f deg\n", pos_err(q_plan_end),
              ang_err(q_plan_end), pos_err(q_end), ang_err(q_end));
  if (settle > 0.0) {
    std::printf("after      %.2f s more: %.4f m %.3f deg from the goal\n", settle, pos_err(state.q),
                ang_err(state.q));
  }
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
