#include "rbsf/planner/kinodynamic/control_sampler.h"

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {

namespace oc = ompl::control;

PhaseControlSampler::PhaseControlSampler(const oc::ControlSpace* space, const RbsfModel& model,
                                         const SimStateSpace& state_space,
                                         const SamplerSettings& settings, double touch_distance)
    : oc::ControlSampler(space),
      model_(model),
      state_space_(state_space),
      settings_(settings),
      targeting_(model, touch_distance) {}

void PhaseControlSampler::write(const VecU& tau, oc::Control* control) const {
  double* u = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  for (int j = 0; j < tau.size(); ++j) u[j] = tau[j];
}

void PhaseControlSampler::randomTau(VecU& tau) {
  const Cell& cell = model_.cell();
  tau.resize(model_.controlDim());
  tau[layout::kTauTheta] = rng_.uniformReal(-cell.base.torque_limit, cell.base.torque_limit);
  for (int i = 0; i < model_.numFingers(); ++i) {
    const double f = cell.fingers[i].force_limit;
    tau[layout::fingerForce(i)] = rng_.uniformReal(-f, f);
  }
}

void PhaseControlSampler::sample(oc::Control* control) {
  VecU tau;
  randomTau(tau);
  write(tau, control);
}

void PhaseControlSampler::sample(oc::Control* control, const ompl::base::State* state) {
  const SamplerSettings& s = settings_;
  VecU tau(model_.controlDim());
  const double u = rng_.uniform01();
  if (u < s.p_random) {
    sample(control);
    return;
  }
  const VecQ q = state_space_.q(state), v = state_space_.v(state);
  const int m = model_.numFingers();
  double stroke_rate = 0.0;
  for (int i = 0; i < m; ++i) stroke_rate += v[layout::stroke(i)];
  stroke_rate /= m;
  const double alpha =
      rng_.uniformReal(-s.max_base_accel, s.max_base_accel) - s.damping * v[layout::kTheta];
  bool ok;
  if (rng_.uniform01() * (s.p_stick + s.p_slide) < s.p_stick) {
    StickTarget t;
    t.base_accel = alpha;
    t.stroke_accel =
        rng_.uniformReal(-s.max_stroke_accel, s.max_stroke_accel) - s.damping * stroke_rate;
    ok = targeting_.stickTau(q, v, t, tau);
  } else {
    SlideTarget t;
    t.base_accel = alpha;
    t.omega_dot = rng_.uniformReal(-s.max_omega_dot, s.max_omega_dot) -
                  s.damping * (v[layout::kPhi] - v[layout::kTheta]);
    t.accel_x = -s.damping * v[layout::kX] - s.centering * (q[layout::kX] - s.home_x);
    t.accel_y = -s.damping * v[layout::kY];
    t.free_stroke_accel = s.max_stroke_accel;  // reach up toward the part
    ok = targeting_.slideTau(q, v, t, tau);
  }
  if (!ok) randomTau(tau);
  write(tau, control);
}

void PhaseControlSampler::sampleNext(oc::Control* control, const oc::Control* /*previous*/,
                                     const ompl::base::State* state) {
  sample(control, state);
}

}  // namespace rbsf::planner
