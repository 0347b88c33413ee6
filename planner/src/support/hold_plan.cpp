#include "rbsf/planner/support/hold_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/planner/support/support_trajectory.h"

namespace rbsf::planner {

std::uint32_t bestHoldingSet(const RbsfModel& model, const VecQ& q0,
                             const BalanceSettings& balance) {
  const int m = model.numFingers();
  const ContactBalancer balancer(model, balance);
  ModelData data(m);
  model.updateContacts(q0, data);
  std::uint32_t touching = 0;
  for (int i = 0; i < m; ++i)
    if (std::abs(data.contacts[i].gap) < 1e-6) touching |= 1u << i;
  std::uint32_t best = 0;
  double best_margin = -std::numeric_limits<double>::infinity();
  for (std::uint32_t set = touching; set != 0; set = (set - 1) & touching) {
    const ContactSet s{set, set};
    if (s.count() < 2) continue;
    const ContactBalance b = balancer.statics(q0, s, data);
    if (!b.balanced || !b.determined || !(b.margin > best_margin)) continue;
    best_margin = b.margin;
    best = set;
  }
  return best;
}

plan::Plan holdPlan(const RbsfModel& model, const VecQ& q0, const HoldSettings& s) {
  if (!(s.duration > 0.0 && s.lift >= 0.0 && s.lift_time > 0.0 && s.lift_time <= s.duration))
    throw InputError("hold plan: duration and lift_time must be positive, lift_time <= duration");
  const int m = model.numFingers();
  const std::uint32_t set = bestHoldingSet(model, q0, s.balance);
  if (set == 0) throw InputError("hold plan: no contact set holds the part at rest there");
  ModelData data(m);
  const ContactBalance b =
      ContactBalancer(model, s.balance).statics(q0, ContactSet{set, set}, data);
  ContactRoles roles{};
  for (int i = 0; i < m; ++i)
    roles[i] = (set >> i) & 1u ? ContactRole::kStick : ContactRole::kLifted;

  ReferenceTrajectory ref;
  const double dt = 0.01;
  const int knots = static_cast<int>(std::ceil(s.duration / dt - 1e-9));
  for (int k = 0; k <= knots; ++k) {
    const double t = std::min(k * dt, s.duration);
    const double u = std::min(t / s.lift_time, 1.0);
    const double p = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
    const double dp = 30.0 * u * u * (1.0 - u) * (1.0 - u) / s.lift_time;
    VecQ q = q0, v = VecQ::Zero(q0.size());
    for (int i = 0; i < m; ++i) {
      if (roles[i] != ContactRole::kLifted) continue;
      q[layout::stroke(i)] -= s.lift * p;
      v[layout::stroke(i)] = -s.lift * dp;
    }
    ref.addKnot(t, q, v);
  }
  ref.addInputPiece(0.0, s.duration, b.tau, VecU(), Phase::kC, roles);
  const Pose pose{q0[layout::kX], q0[layout::kY], q0[layout::kPhi]};
  return closedLoopPlan(model, ref, s.simulator, s.feedback, pose, 0.01, 2.0 * M_PI / 180, 10);
}

}  // namespace rbsf::planner
