#include "rbsf/dynamics/tracking_controller.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/state_layout.h"

namespace rbsf {

TrackingController::TrackingController(const RbsfModel& model, const VecQ& q_nominal,
                                       const TrackingSettings& settings) {
  const double w = settings.natural_frequency, z = settings.damping_ratio;
  if (!std::isfinite(w) || !(w > 0.0))
    throw InputError("tracking natural_frequency must be positive");
  if (!std::isfinite(z) || z < 0.0) throw InputError("tracking damping_ratio must be non-negative");
  if (q_nominal.size() != model.configDim())
    throw InputError("tracking controller: nominal configuration of wrong size");
  const int m = model.numFingers();
  limit_.resize(layout::controlDim(m));
  limit_[layout::kTauTheta] = model.cell().base.torque_limit;
  for (int i = 0; i < m; ++i) limit_[layout::fingerForce(i)] = model.cell().fingers[i].force_limit;
  const VecU inertia = effectiveInertia(model, q_nominal);
  setGains(inertia * (w * w), inertia * (2.0 * z * w));
}

VecU TrackingController::effectiveInertia(const RbsfModel& model, const VecQ& q) {
  const Cell& c = model.cell();
  const int m = model.numFingers();
  MatQQ M;
  model.massMatrix(q, M);
  VecU inertia(layout::controlDim(m));
  const double r2 = q[layout::kX] * q[layout::kX] + q[layout::kY] * q[layout::kY];
  inertia[layout::kTauTheta] =
      M(layout::kTheta, layout::kTheta) + c.object.inertia + c.object.mass * r2;
  for (int i = 0; i < m; ++i)
    inertia[layout::fingerForce(i)] = c.fingers[i].mass + c.object.mass / m;
  return inertia;
}

void TrackingController::setGains(const VecU& kp, const VecU& kd) {
  if (kp.size() != limit_.size() || kd.size() != limit_.size())
    throw InputError("tracking gains must have m + 1 entries");
  if (!kp.allFinite() || !kd.allFinite() || kp.minCoeff() < 0.0 || kd.minCoeff() < 0.0)
    throw InputError("tracking gains must be finite and non-negative");
  kp_ = kp;
  kd_ = kd;
}

bool TrackingController::compute(const VecQ& q, const VecQ& v, const ReferenceSample& ref,
                                 VecU& tau) const {
  const int nu = static_cast<int>(limit_.size());
  tau.resize(nu);
  bool clamped = false;
  for (int j = 0; j < nu; ++j) {
    const int k = layout::inputToConfig(j);
    const double u = ref.tau[j] + kp_[j] * (ref.q[k] - q[k]) + kd_[j] * (ref.v[k] - v[k]);
    tau[j] = std::clamp(u, -limit_[j], limit_[j]);
    clamped = clamped || tau[j] != u;
  }
  return clamped;
}

double TrackingController::jointError(const VecQ& q, const ReferenceSample& ref) {
  double e = 0.0;
  for (int k = layout::kTheta; k < q.size(); ++k) e = std::max(e, std::abs(ref.q[k] - q[k]));
  return e;
}

}  // namespace rbsf
