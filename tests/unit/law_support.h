#pragma once
// Cells and plans for the tests of the control law and the certificate.

#include <cmath>

#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/plan/plan.h"
#include "rbsf/planner/support/hold_plan.h"
#include "test_support.h"

namespace rbsf::test {

/// Two frictionless fingers 6 cm either side of the base axis under the default cell's
/// part (an ellipse 0.6 m by 0.3 m, its COM at its centre here) standing on its end: the
/// part rides on two sliding tips, balanced like an inverted pendulum (the normals meet
/// below its COM).
inline Cell twoTipsCell() {
  Cell c;
  c.gravity = 9.81;
  c.base = {5.0, -0.785398, 0.785398, 400.0};
  for (double r : {-0.06, 0.06}) {
    FingerParams f;
    f.r = r;
    f.stroke_min = 0.05;
    f.stroke_max = 0.55;
    f.mass = 2.0;
    f.force_limit = 800.0;
    c.fingers.push_back(f);
  }
  c.object.shape = std::make_shared<EllipseShape>(0.30, 0.15);
  c.object.mass = 24.0;
  c.object.inertia = 0.675;
  c.friction = {0.0, 0.0};
  // Balanced on frictionless tips under the camera's noise the part is held, never still:
  // the feedback keeps it within a centimetre of its pose, moving up to 1.5 cm/s and
  // 1.5 deg/s over the last second. This cell's rest says so.
  c.motion_limits.rest_speed = 0.02;
  c.motion_limits.rest_angular_speed = 2.0 * M_PI / 180.0;
  c.name = "two tips";
  return c;
}

/// The part of twoTipsCell() balanced upright at (0, 0.5) on its tips, base at theta.
inline VecQ twoTipsConfiguration(const RbsfModel& model, double theta) {
  return restingConfiguration(model, Pose{0.0, 0.5, M_PI / 2}, theta);
}

/// A plan that slides the part on the two tips: the base tilts by `amplitude` and back
/// (theta = amplitude sin^2(pi t / T)) with the part's pose asked to stay, so the tips slide
/// under it (about 1 cm for 1 deg). Made by the part-feedback law on the exact state: the
/// plan is that closed loop's simulation, in 1 ms segments, a sample every step.
inline plan::Plan twoTipsPlan(const RbsfModel& model, double amplitude = M_PI / 180,
                              double duration = 3.0) {
  const int m = model.numFingers();
  const double h = 1e-3;
  const VecQ q0 = twoTipsConfiguration(model, 0.0);
  ModelData data(m);
  model.updateContacts(q0, data);
  const VecU hold = holdingTorques(model, q0, data).tau;
  auto at = [&](double t) {
    const double s = std::sin(M_PI * t / duration);
    return twoTipsConfiguration(model, amplitude * s * s);
  };
  ReferenceTrajectory wanted;
  const long steps = std::lround(duration / h);
  for (long j = 0; j <= steps; ++j) {
    const double t = j * h;
    wanted.addKnot(t, at(t), (at(t + 1e-6) - at(t - 1e-6)) / 2e-6);
  }
  wanted.addInputPiece(0.0, duration, hold, VecU(), Phase::kU);
  FeedbackSettings fs;
  fs.timing.settle_time = 0.0;
  const FeedbackSchedule schedule(model, wanted, Sensing{}, SimulatorSettings{}, fs);
  ControlLaw law(schedule);
  const Simulator simulator(model);
  SimulatorWorkspace ws(m);
  SimState state(q0, VecQ::Zero(q0.size()));
  plan::Plan plan;
  plan.status = plan::PlanStatus::kExact;
  plan.planner = "test: the part-feedback law on the exact state";
  plan.q0 = q0;
  plan.start = {q0[0], q0[1], q0[2]};
  auto sample = [&](const SimState& s, const VecU& tau, const StepReport* r) {
    plan::PlanSample x;
    x.t = s.t;
    x.q = s.q;
    x.v = s.v;
    x.tau = tau;
    x.f_n = VecC::Zero(m);
    for (int i = 0; r && i < m; ++i) x.f_n[i] = r->contacts[i].f_n;
    x.phase = r ? r->phase : Phase::kU;
    plan.samples.push_back(x);
  };
  sample(state, hold, nullptr);
  rollout(
      simulator, state, steps, ws,
      [&](const SimState& s, long n, VecU& tau) {
        law.computeFromState(static_cast<double>(n) * h, s.q, s.v, tau);
        return true;
      },
      [&](const SimState& s, const StepReport& r, const VecU& tau, long) {
        plan::PlanSegment seg;
        seg.phase = r.phase == Phase::kC || r.phase == Phase::kP ? r.phase : Phase::kU;
        seg.steps = 1;
        seg.duration = h;
        seg.tau = tau;
        plan.segments.push_back(seg);
        sample(s, tau, &r);
        return true;
      });
  plan.goal = {state.q[0], state.q[1], state.q[2]};
  return plan;
}

/// twoTipsCell()'s model and its default twoTipsPlan(), built once per test binary.
inline const RbsfModel& sharedTwoTipsModel() {
  static const RbsfModel model(twoTipsCell());
  return model;
}
inline const plan::Plan& sharedTwoTipsPlan() {
  static const plan::Plan plan = twoTipsPlan(sharedTwoTipsModel());
  return plan;
}

/// A plan that holds the part at rest at q0 for `duration` on the set that holds it best
/// (planner/hold_plan.h), its law the one the cell's sensing allows.
inline plan::Plan holdPlan(const RbsfModel& model, const VecQ& q0, double duration) {
  planner::HoldSettings s;
  s.duration = duration;
  s.lift_time = std::min(s.lift_time, duration);
  plan::Plan plan = planner::holdPlan(model, q0, s);
  plan.joint_feedback = false;
  return plan;
}

/// A plan that keeps the part at q0 for `duration` with the holding torques of every contact
/// (holdingTorques; two samples, one segment): the balance of a part on frictionless tips.
inline plan::Plan restPlan(const RbsfModel& model, const VecQ& q0, double duration) {
  ModelData data(model.numFingers());
  model.updateContacts(q0, data);
  plan::Plan plan;
  plan.status = plan::PlanStatus::kExact;
  plan.q0 = q0;
  plan.start = plan.goal = {q0[0], q0[1], q0[2]};
  plan::PlanSegment seg;
  seg.phase = Phase::kC;
  seg.steps = static_cast<int>(std::lround(duration / plan.simulator.time_step));
  seg.duration = duration;
  seg.tau = holdingTorques(model, q0, data).tau;
  plan.segments.push_back(seg);
  for (double t : {0.0, duration}) {
    plan::PlanSample s;
    s.t = t;
    s.q = q0;
    s.v = VecQ::Zero(q0.size());
    s.tau = seg.tau;
    s.f_n = VecC::Zero(model.numFingers());
    s.phase = Phase::kC;
    plan.samples.push_back(s);
  }
  return plan;
}

}  // namespace rbsf::test
