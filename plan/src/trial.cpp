#include "rbsf/plan/trial.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>

#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/control/sensor_model.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::plan {

namespace {

/// SplitMix64: decorrelates the generators of neighbouring trials and seeds.
std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

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
  std::mt19937_64 rng(splitmix(splitmix(seed) ^ static_cast<std::uint64_t>(index)));
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

TrialOutcome runTrial(const FeedbackSchedule& schedule, const Plan& plan, const TrialDraw& draw,
                      const TrialSettings& s, bool open_loop,
                      std::vector<TrajectorySample>* trace) {
  const RbsfModel plant(draw.cell);
  const Simulator simulator(plant, plan.simulator);
  const int m = plant.numFingers(), nu = plant.controlDim();
  if (plan.q0.size() != plant.configDim())
    throw InputError("the plan is for " + std::to_string(plan.q0.size() - 4) +
                     " fingers, the cell has " + std::to_string(m));
  const double h = plan.simulator.time_step;
  auto ws = std::make_unique<SimulatorWorkspace>(m);
  SimState state(draw.q0, VecQ::Zero(draw.q0.size()));
  ControlLaw law(schedule);
  SensorModel sensors(schedule.sensing(), h, draw.noise_seed, draw.noise, draw.com_offset);

  const long steps = std::lround(schedule.holdEnd() / h);
  const long rest_steps = std::max(1L, std::min(steps, std::lround(s.rest_window / h)));
  auto framePose = [&](const VecQ& q) {
    const Pose p = sensors.framePose(q);
    return Eigen::Vector3d(p.x, p.y, p.phi);
  };

  TrialOutcome r;
  ReferenceSample ref, mid;
  VecU joints(nu);
  long saturated = 0, untouched = 0;
  double min_fn = std::numeric_limits<double>::infinity();
  std::vector<std::pair<Phase, double>> runs;
  Eigen::Vector3d window_start = framePose(state.q);

  auto input = [&](const SimState& now, long n, VecU& tau) {
    const double t = static_cast<double>(n) * h;
    if (open_loop) {
      schedule.reference(t + 0.5 * h, mid);
      tau = mid.tau;
      for (int j = 0; j < nu; ++j)
        if (std::abs(tau[j]) > plant.cell().inputLimit(j)) {
          ++saturated;
          break;
        }
    } else {
      sensors.joints(now.q, joints);
      sensors.partPose(n, now.q, [&](double stamp, const Pose& p) { law.addPartPose(stamp, p); });
      if (law.compute(t, joints, tau)) ++saturated;
    }
    for (int j = 0; j < nu; ++j) tau[j] *= draw.actuator_gain[j];
    return true;
  };
  auto observe = [&](const SimState& now, const StepReport& report, const VecU& tau, long n) {
    const double t = static_cast<double>(n + 1) * h;
    if (trace) trace->push_back(trajectorySample(now, report, tau));
    for (int i = 0; i < m; ++i)
      if (report.contacts[i].mode != ContactMode::kSeparated)
        min_fn = std::min(min_fn, report.contacts[i].f_n);
    const Phase ph = report.phase == Phase::kUnsupported ? Phase::kU : report.phase;
    if (!runs.empty() && runs.back().first == ph)
      runs.back().second += h;
    else
      runs.emplace_back(ph, h);
    untouched = report.touching == 0 ? untouched + 1 : 0;
    const Eigen::Vector3d p = framePose(now.q);
    schedule.reference(t, ref);
    const double dp = std::hypot(p[0] - ref.q[layout::kX], p[1] - ref.q[layout::kY]);
    const double da = std::abs(p[2] - ref.q[layout::kPhi]);
    r.max_deviation =
        std::max(r.max_deviation, std::max(dp / s.position_tolerance, da / s.angle_tolerance));
    if (r.departure_time < 0.0 && !(dp <= s.position_tolerance && da <= s.angle_tolerance)) {
      r.departure_time = t;
      r.departure_phase = t > schedule.planEnd() ? "hold" : std::string(1, letter(ref.phase));
    }
    if (n + 1 == steps - rest_steps) window_start = p;
    const bool lost = !now.q.allFinite() || !now.v.allFinite() || !(dp <= s.lost_distance) ||
                      static_cast<double>(untouched) * h >= s.drop_time;
    if (lost) {
      r.dropped = true;
      r.dropped_time = t;
    }
    return !lost;
  };
  const long taken = rollout(simulator, state, steps, *ws, input, observe);

  r.saturated_time = static_cast<double>(saturated) * h;
  r.min_f_n = std::isfinite(min_fn) ? min_fn : 0.0;
  r.phases = filterPhaseRuns(runs, s.min_phase_run);
  const Eigen::Vector3d p = state.q.allFinite() ? framePose(state.q) : Eigen::Vector3d::Zero();
  r.position_error = std::hypot(p[0] - plan.goal.x, p[1] - plan.goal.y);
  schedule.reference(schedule.planEnd(), ref);
  const double goal_phi = ref.q[layout::kPhi] + angleDifference(plan.goal.phi, ref.q[layout::kPhi]);
  r.angle_error = std::abs(p[2] - goal_phi);
  if (taken == steps) {
    const double w = static_cast<double>(rest_steps) * h;
    r.speed = std::hypot(p[0] - window_start[0], p[1] - window_start[1]) / w;
    r.angular_speed = std::abs(p[2] - window_start[2]) / w;
  }
  if (!state.q.allFinite()) r.position_error = r.angle_error = r.speed = r.angular_speed = 0.0;

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
  const MotionLimits& rest = schedule.model().cell().motion_limits;
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
  return r;
}

}  // namespace rbsf::plan
