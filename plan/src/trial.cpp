#include "rbsf/plan/trial.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>

#include "rbsf/dynamics/control/plan_executor.h"
#include "rbsf/dynamics/control/sensor_model.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::plan {

namespace {

/// The true COM pose of a part whose frame is at `frame` and whose COM sits at d in it.
Pose comPose(const Pose& frame, const Vec2& d) {
  const Vec2 c = Vec2(frame.x, frame.y) + rotate(frame.phi, d);
  return {c.x(), c.y(), frame.phi};
}

char letter(Phase p) { return p == Phase::kC ? 'C' : p == Phase::kP ? 'P' : 'U'; }

}  // namespace

TrialDraw nominalDraw(const Cell& cell, const Plan& plan) {
  TrialDraw d;
  d.cell = cell;
  d.com_offset = Vec2::Zero();
  d.q0 = plan.q0;
  d.actuator_gain = VecU::Ones(static_cast<int>(plan.q0.size()) - 3);
  d.noise = false;
  return d;
}

TrialDraw drawTrial(const Cell& cell, const Plan& plan, std::uint64_t seed, int index) {
  std::mt19937_64 rng(splitMix64(splitMix64(seed) ^ static_cast<std::uint64_t>(index)));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Uncertainty& un = cell.uncertainty;
  TrialDraw d;
  d.cell = cell;
  Cell& c = d.cell;
  c.object.mass *= 1.0 + un.mass * u(rng);
  c.object.inertia *= 1.0 + un.inertia * u(rng);
  const double dx = un.com * u(rng), dy = un.com * u(rng);
  d.com_offset = Vec2(dx, dy);
  c.object.shape = cell.object.shape->shifted(-d.com_offset);
  const double friction = 1.0 + un.static_friction * u(rng);
  c.friction.mu_static = cell.friction.mu_static * friction;
  const double k = 0.5 * (u(rng) + 1.0);
  c.friction.mu_kinetic =
      cell.friction.mu_kinetic == 0.0
          ? un.kinetic_friction_min + k * (un.kinetic_friction_max - un.kinetic_friction_min)
          : cell.friction.mu_kinetic * friction;
  c.friction.mu_kinetic = std::min(c.friction.mu_kinetic, c.friction.mu_static);
  const Pose frame{plan.q0[layout::kX] + un.initial_position * u(rng),
                   plan.q0[layout::kY] + un.initial_position * u(rng),
                   plan.q0[layout::kPhi] + un.initial_angle * u(rng)};
  const int nu = static_cast<int>(plan.q0.size()) - 3;
  d.actuator_gain.resize(nu);
  for (int j = 0; j < nu; ++j) d.actuator_gain[j] = 1.0 + un.actuator_gain * u(rng);
  d.noise_seed = rng();
  // Over the plan and a generous settle hold: events past the run are never reached.
  const double h = plan.simulator.time_step;
  d.faults = drawFaults(cell.faults, plan, seed, index, std::lround((plan.duration() + 5.0) / h), h,
                        static_cast<int>(plan.q0.size()) - 3);
  c.object.mass *= 1.0 + d.faults.mass_error;
  const RbsfModel plant(c);
  const double theta = plan.q0[layout::kTheta];
  try {
    d.q0 = restingConfiguration(plant, comPose(frame, d.com_offset), theta);
  } catch (const InputError&) {
    // A drawn start a finger cannot reach: the plan's own start pose instead.
    const Pose start{plan.q0[layout::kX], plan.q0[layout::kY], plan.q0[layout::kPhi]};
    d.q0 = restingConfiguration(plant, comPose(start, d.com_offset), theta);
  }
  return d;
}

namespace {

/// The failures of outcome `r` under `s` and the cell's rest limits `rest` (in this order:
/// dropped, position, angle, not at rest, saturated), and its success.
void judge(const TrialSettings& s, const MotionLimits& rest, TrialOutcome& r) {
  char buf[160];
  auto fail = [&](const char* what) {
    r.failure += (r.failure.empty() ? "" : "; ") + std::string(what);
  };
  if (r.dropped) {
    std::snprintf(buf, sizeof buf, "part dropped at t = %.3f s", r.dropped_time);
    fail(buf);
  }
  if (!(r.position_error <= s.position_tolerance)) {
    std::snprintf(buf, sizeof buf, "ends %.3g m from the goal (> %.3g m)", r.position_error,
                  s.position_tolerance);
    fail(buf);
  }
  if (!(r.angle_error <= s.angle_tolerance)) {
    std::snprintf(buf, sizeof buf, "ends %.3g deg from the goal angle (> %.3g deg)",
                  r.angle_error * 180 / M_PI, s.angle_tolerance * 180 / M_PI);
    fail(buf);
  }
  if (!r.dropped && !(r.speed <= rest.rest_speed && r.angular_speed <= rest.rest_angular_speed)) {
    std::snprintf(buf, sizeof buf, "not at rest (%.3g m/s, %.3g deg/s)", r.speed,
                  r.angular_speed * 180 / M_PI);
    fail(buf);
  }
  if (r.saturated_time > s.saturation_time) {
    std::snprintf(buf, sizeof buf, "inputs at their limits for %.3g s", r.saturated_time);
    fail(buf);
  }
  r.success = r.failure.empty();
}

/// One runTrial() in progress: the plant's law and sensors and what the rollout's steps have
/// seen so far; run() once per object.
class TrialRun {
 public:
  TrialRun(const FeedbackSchedule& schedule, const Plan& plan, const TrialDraw& draw,
           const TrialSettings& s, const RbsfModel& plant, bool open_loop,
           std::vector<TrajectorySample>* trace)
      : schedule_(schedule),
        plan_(plan),
        draw_(draw),
        s_(s),
        plant_(plant),
        open_loop_(open_loop),
        trace_(trace),
        m_(plant.numFingers()),
        nu_(plant.controlDim()),
        h_(plan.simulator.time_step),
        exec_(schedule, limitsFor(s.execution, draw.faults)),
        faults_(draw.faults),
        fault_flags_(flagsOf(draw.faults)),
        sensors_(schedule.sensing(), h_, draw.noise_seed, draw.noise, draw.com_offset),
        camera_(schedule.model().cell().sensing, h_, splitMix64(draw.noise_seed), draw.noise,
                draw.com_offset),
        status_camera_(!schedule.partFeedback() &&
                       schedule.model().cell().sensing.part_pose.present),
        steps_(std::lround(schedule.holdEnd() / h_)),
        rest_steps_(std::max(1L, std::min(steps_, std::lround(s.rest_window / h_)))),
        joints_(nu_) {}

  /// The trial on `simulator` (the plant's), measured at its end and judged (judge()).
  TrialOutcome run(const Simulator& simulator) {
    auto ws = std::make_unique<SimulatorWorkspace>(m_);
    const long first_fault = draw_.faults.firstStep();
    if (first_fault >= 0) r_.fault_time = static_cast<double>(first_fault) * h_;
    SimState state(draw_.q0, VecQ::Zero(draw_.q0.size()));
    window_start_ = framePose(state.q);
    const long taken = rollout(
        simulator, state, steps_, *ws,
        [this](const SimState& now, long n, VecU& tau) { return input(now, n, tau); },
        [this](const SimState& now, const StepReport& report, const VecU& tau, long n) {
          return observe(now, report, tau, n);
        });
    measureEnd(state, taken);
    judge(s_, schedule_.model().cell().motion_limits, r_);
    return r_;
  }

 private:
  /// The sensed frame pose (x, y, phi) of the part at `q`.
  Eigen::Vector3d framePose(const VecQ& q) const {
    const Pose p = sensors_.framePose(q);
    return Eigen::Vector3d(p.x, p.y, p.phi);
  }
  /// The execution limits of a trial: its settings', with the holds on when it draws faults.
  static ExecutionLimits limitsFor(ExecutionLimits limits, const FaultDraw& faults) {
    if (faults.any()) limits.hold_on_leaving = limits.hold_on_faults = true;
    return limits;
  }
  /// The status flags by which the status sees the faults drawn.
  static std::uint32_t flagsOf(const FaultDraw& f) {
    std::uint32_t flags = 0;
    if (!f.dropouts.empty()) flags |= kFlagStalePose;
    if (!f.spikes.empty()) flags |= kFlagBadJoints | kFlagStrokeError | kFlagDeviation;
    if (!f.missed.empty()) flags |= kFlagLateTick;
    if (f.cut_step >= 0 || f.mass_error != 0.0)
      flags |= kFlagSaturated | kFlagDeviation | kFlagStrokeError | kFlagOffTube;
    return flags;
  }
  /// The rollout input of step n: the reference's (open loop) or the law's, times the drawn
  /// actuator gains, through the drawn faults; counts the steps at the input limits.
  bool input(const SimState& now, long n, VecU& tau);
  /// Keeps what the execution status of a tick says in the outcome.
  void watch(const ExecutionStatus& status);
  /// The rollout observer after step n: records it, follows the reference and tells whether
  /// the part is lost (false stops the trial).
  bool observe(const SimState& now, const StepReport& report, const VecU& tau, long n);
  /// Records the step: the trace, the lowest normal force, the phase runs, the steps
  /// without touch.
  void record(const SimState& now, const StepReport& report, const VecU& tau);
  /// The deviation of frame pose `p` from the reference at time t, and where the part first
  /// left the planned path; returns the position deviation.
  double follow(const Eigen::Vector3d& p, double t);
  /// The outcome's measures at the end of the `taken` steps: saturation, force, phases,
  /// errors to the goal and, when the trial ran to the end, the speeds over the rest window.
  void measureEnd(const SimState& state, long taken);

  const FeedbackSchedule& schedule_;
  const Plan& plan_;
  const TrialDraw& draw_;
  const TrialSettings& s_;
  const RbsfModel& plant_;
  const bool open_loop_;
  std::vector<TrajectorySample>* trace_;
  const int m_, nu_;
  const double h_;
  PlanExecutor exec_;
  FaultInjector faults_;
  const std::uint32_t fault_flags_;
  VecU last_tau_;  ///< the law's last input (a missed tick holds it)
  SensorModel sensors_;
  /// The cell's own part-pose sensor where the law runs on the joints alone: its poses serve
  /// the execution status, not the law (its own generator: the law's measurements are
  /// those of a trial without it).
  SensorModel camera_;
  const bool status_camera_;
  const long steps_, rest_steps_;
  TrialOutcome r_;
  ReferenceSample ref_, mid_;
  VecU joints_;
  long saturated_ = 0, untouched_ = 0;
  double min_fn_ = std::numeric_limits<double>::infinity();
  std::vector<std::pair<Phase, double>> runs_;
  Eigen::Vector3d window_start_;  ///< frame pose at the start of the rest window
};

bool TrialRun::input(const SimState& now, long n, VecU& tau) {
  const double t = static_cast<double>(n) * h_;
  if (open_loop_) {
    schedule_.reference(t + 0.5 * h_, mid_);
    tau = mid_.tau;
    for (int j = 0; j < nu_; ++j)
      if (std::abs(tau[j]) > plant_.cell().inputLimit(j)) {
        ++saturated_;
        break;
      }
  } else if (faults_.missed(n) && last_tau_.size() == nu_) {
    tau = last_tau_;  // the loop skipped this tick: the actuators hold the last input
  } else {
    sensors_.joints(now.q, joints_);
    faults_.corruptJoints(n, joints_);
    auto deliver = [&](double stamp, const Pose& p) {
      if (!faults_.dropped(std::lround(stamp / h_))) exec_.addPartPose(stamp, p);
    };
    sensors_.partPose(n, now.q, deliver);
    if (status_camera_) camera_.partPose(n, now.q, deliver);
    exec_.step(t, joints_, tau);
    watch(exec_.status());
    if (exec_.status().saturated) ++saturated_;
    last_tau_ = tau;
  }
  for (int j = 0; j < nu_; ++j) tau[j] *= draw_.actuator_gain[j];
  faults_.cut(n, plant_.cell(), tau);
  return true;
}

bool TrialRun::observe(const SimState& now, const StepReport& report, const VecU& tau, long n) {
  const double t = static_cast<double>(n + 1) * h_;
  record(now, report, tau);
  const Eigen::Vector3d p = framePose(now.q);
  const double dp = follow(p, t);
  if (n + 1 == steps_ - rest_steps_) window_start_ = p;
  const bool lost = !now.q.allFinite() || !now.v.allFinite() || !(dp <= s_.lost_distance) ||
                    static_cast<double>(untouched_) * h_ >= s_.drop_time;
  if (lost) {
    r_.dropped = true;
    r_.dropped_time = t;
  }
  return !lost;
}

void TrialRun::record(const SimState& now, const StepReport& report, const VecU& tau) {
  if (trace_) trace_->push_back(trajectorySample(now, report, tau));
  for (int i = 0; i < m_; ++i)
    if (report.contacts[i].mode != ContactMode::kSeparated)
      min_fn_ = std::min(min_fn_, report.contacts[i].f_n);
  const Phase ph = report.phase == Phase::kUnsupported ? Phase::kU : report.phase;
  if (!runs_.empty() && runs_.back().first == ph)
    runs_.back().second += h_;
  else
    runs_.emplace_back(ph, h_);
  untouched_ = report.touching == 0 ? untouched_ + 1 : 0;
}

void TrialRun::watch(const ExecutionStatus& st) {
  r_.status_position = std::max(r_.status_position, st.position_deviation);
  r_.status_angle = std::max(r_.status_angle, st.angle_deviation);
  r_.status_stroke = std::max(r_.status_stroke, st.stroke_deviation);
  r_.status_stroke_speed = std::max(r_.status_stroke_speed, st.stroke_speed_deviation);
  if (r_.leaving_time < 0.0 && st.verdict == ExecutionVerdict::kLeaving)
    r_.leaving_time = st.plan_time;
  if (r_.hold == HoldReason::kNone && st.hold_reason != HoldReason::kNone) {
    r_.hold = st.hold_reason;
    r_.hold_time = st.hold_time;
  }
  r_.final_verdict = st.verdict;
  if (r_.report_time < 0.0 &&
      (st.verdict == ExecutionVerdict::kLeaving || st.verdict == ExecutionVerdict::kHolding))
    r_.report_time = st.plan_time;
  if (r_.fault_time >= 0.0 && r_.fault_seen_time < 0.0 && st.plan_time >= r_.fault_time &&
      (st.flags & fault_flags_) != 0)
    r_.fault_seen_time = st.plan_time;
}

double TrialRun::follow(const Eigen::Vector3d& p, double t) {
  schedule_.reference(t, ref_);
  const double dp = std::hypot(p[0] - ref_.q[layout::kX], p[1] - ref_.q[layout::kY]);
  const double da = std::abs(p[2] - ref_.q[layout::kPhi]);
  r_.max_deviation =
      std::max(r_.max_deviation, std::max(dp / s_.position_tolerance, da / s_.angle_tolerance));
  if (r_.departure_time < 0.0 && !(dp <= s_.position_tolerance && da <= s_.angle_tolerance)) {
    r_.departure_time = t;
    r_.departure_phase = t > schedule_.planEnd() ? "hold" : std::string(1, letter(ref_.phase));
  }
  return dp;
}

void TrialRun::measureEnd(const SimState& state, long taken) {
  r_.saturated_time = static_cast<double>(saturated_) * h_;
  r_.min_f_n = std::isfinite(min_fn_) ? min_fn_ : 0.0;
  r_.phases = filterPhaseRuns(runs_, s_.min_phase_run);
  const Eigen::Vector3d p = state.q.allFinite() ? framePose(state.q) : Eigen::Vector3d::Zero();
  r_.position_error = std::hypot(p[0] - plan_.goal.x, p[1] - plan_.goal.y);
  schedule_.reference(schedule_.planEnd(), ref_);
  const double goal_phi =
      ref_.q[layout::kPhi] + angleDifference(plan_.goal.phi, ref_.q[layout::kPhi]);
  r_.angle_error = std::abs(p[2] - goal_phi);
  if (taken == steps_) {
    const double w = static_cast<double>(rest_steps_) * h_;
    r_.speed = std::hypot(p[0] - window_start_[0], p[1] - window_start_[1]) / w;
    r_.angular_speed = std::abs(p[2] - window_start_[2]) / w;
  }
  if (!state.q.allFinite()) r_.position_error = r_.angle_error = r_.speed = r_.angular_speed = 0.0;
}

}  // namespace

TrialOutcome runTrial(const FeedbackSchedule& schedule, const Plan& plan, const TrialDraw& draw,
                      const TrialSettings& s, bool open_loop,
                      std::vector<TrajectorySample>* trace) {
  const RbsfModel plant(draw.cell);
  const Simulator simulator(plant, plan.simulator);
  if (plan.q0.size() != plant.configDim())
    throw InputError("the plan is for " + std::to_string(plan.q0.size() - 4) +
                     " fingers, the cell has " + std::to_string(plant.numFingers()));
  return TrialRun(schedule, plan, draw, s, plant, open_loop, trace).run(simulator);
}

}  // namespace rbsf::plan
