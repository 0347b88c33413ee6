#include "rbsf/plan/plan_holding.h"

#include <cmath>
#include <cstdio>

#include "rbsf/dynamics/core/contact_balance.h"
#include "rbsf/plan/plan.h"

namespace rbsf::plan {

PlanHolding measureHolding(const RbsfModel& model, const Plan& plan, const HoldingSettings& s) {
  PlanHolding h;
  h.max_free_time = s.max_free_time;
  if (plan.samples.empty()) return h;
  h.measured = true;
  const ContactBalancer balancer(model);
  const int m = model.numFingers();
  ModelData data(m);
  double last_held = plan.samples.front().t;  // the last determined sample's time
  bool free = false;
  auto close = [&](double end) {
    const double length = end - last_held;
    h.free_time += length;
    if (length > h.longest_free) h.longest_free = length, h.longest_free_start = last_held;
  };
  for (const TrajectorySample& sample : plan.samples) {
    model.updateContacts(sample.q, data);
    ContactSet set;
    for (int i = 0; i < m; ++i) {
      if (!(sample.f_n[i] > s.touch_force)) continue;
      set.touching |= 1u << i;
      if (std::abs(data.T.col(i).dot(sample.v)) <= s.slip_rate) set.sticking |= 1u << i;
    }
    const bool held = set.rows() >= 3 && balancer.determined(set, data);
    if (held) {
      if (free) close(sample.t);
      free = false;
      last_held = sample.t;
    } else {
      free = true;
    }
  }
  if (free) close(plan.samples.back().t);
  return h;
}

std::string holdingText(const PlanHolding& h) {
  char buf[256];
  if (!h.measured) return "holding: not judged";
  if (h.ok())
    std::snprintf(buf, sizeof buf,
                  "holding: the joints fix the part throughout (free %.3g s in all, longest "
                  "%.3g s; allowed %.3g s)",
                  h.free_time, h.longest_free, h.max_free_time);
  else
    std::snprintf(buf, sizeof buf,
                  "holding: NOT BY THE JOINTS ALONE: the part is free for %.3g s from t = %.3g s "
                  "(allowed %.3g s; %.3g s in all)",
                  h.longest_free, h.longest_free_start, h.max_free_time, h.free_time);
  return buf;
}

}  // namespace rbsf::plan
