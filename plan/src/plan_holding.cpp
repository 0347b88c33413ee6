#include "rbsf/plan/plan_holding.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

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
  // Each sample's contact points in the part's frame, for the slips between samples.
  const std::size_t N = plan.samples.size();
  std::vector<std::array<Vec2, kMaxFingers>> points(N);
  for (std::size_t k = 0; k < N; ++k) {
    model.updateContacts(plan.samples[k].q, data);
    for (int i = 0; i < m; ++i) points[k][i] = model.shape().point(data.contacts[i].xi);
  }
  // The mean slip of contact i from sample a to sample b [m/s]: how far its point moved on
  // the part.
  auto meanSlip = [&](std::size_t a, std::size_t b, int i) {
    const double dt = plan.samples[b].t - plan.samples[a].t;
    return dt > 0.0 ? (points[b][i] - points[a][i]).norm() / dt : 0.0;
  };
  for (std::size_t k = 0; k < N; ++k) {
    const TrajectorySample& sample = plan.samples[k];
    model.updateContacts(sample.q, data);
    ContactSet set;
    for (int i = 0; i < m; ++i) {
      if (!(sample.f_n[i] > s.touch_force)) continue;
      set.touching |= 1u << i;
      const bool still = std::abs(data.T.col(i).dot(sample.v)) <= s.slip_rate;
      const bool kept = (k == 0 || meanSlip(k - 1, k, i) <= s.slip_rate) &&
                        (k + 1 == N || meanSlip(k, k + 1, i) <= s.slip_rate);
      if (still || kept) set.sticking |= 1u << i;
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
