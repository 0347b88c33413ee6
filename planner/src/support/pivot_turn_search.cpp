// PivotTurnSearch: the pivots of a path, the rigid runs and the finish of a simple turn;
// search() is defined with its Run (pivot_turn_search_run.cpp) so that the private run header
// and this source do not include each other.
#include "rbsf/planner/support/pivot_turn_search.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rbsf::planner {

int pivotRuns(const std::vector<SupportStep>& steps) {
  int pivots = 0;
  for (std::size_t k = 0; k < steps.size(); ++k)
    if (steps[k].set.pivot() >= 0 && (k == 0 || steps[k].set != steps[k - 1].set)) ++pivots;
  return pivots;
}

std::vector<ContactSet> restSetsWithin(std::uint32_t reach, int m, int max_sliders) {
  std::vector<ContactSet> sets;
  for (std::uint32_t t = reach; t != 0; t = (t - 1) & reach) {
    const int n = ContactSet::bitCount(t);
    if (n < 2) continue;
    sets.push_back(ContactSet{t, t});
    if (n - 1 > max_sliders) continue;
    for (int k = 0; k < m; ++k)
      if ((t >> k) & 1u) sets.push_back(ContactSet{t, 1u << k});
  }
  return sets;
}

PivotTurnSearch::PivotTurnSearch(SupportSearch& search, PivotTurnSettings settings)
    : search_(search), settings_(settings) {}

std::vector<SupportStep> PivotTurnSearch::rigidRun(const SupportStep& from, double theta) {
  const double span = std::abs(theta - from.pose.theta) / settings_.angle_step;
  const int n = std::max(1, static_cast<int>(std::ceil(span - 1e-9)));
  std::vector<SupportStep> out;
  SupportStep prev = from, next;
  for (int k = 1; k <= n; ++k) {
    JigPose pose = from.pose;
    pose.theta += (theta - from.pose.theta) * static_cast<double>(k) / n;
    if (!search_.stepTo(prev, pose, from.set, from.anchor, next)) return {};
    out.push_back(next);
    prev = next;
  }
  return out;
}

std::vector<SupportStep> PivotTurnSearch::finish(const SupportStep& at, double psi, double theta,
                                                 double l) {
  std::vector<SupportStep> out = search_.straightPivot(at, psi, at.pose.theta, l);
  if (out.empty() || std::abs(out.back().pose.theta - theta) < 1e-9) return out;
  const SupportStep end = out.back();
  // At rest, two or more tips stick and the base turns onto the goal: of the sets that can,
  // the one whose smallest margin along the way is largest (the run ends the plan, at rest).
  const std::uint32_t reachable =
      end.set.touching | search_.geometry().placedSet(end.pose).touching;
  std::vector<SupportStep> best;
  double best_margin = -1.0;
  for (std::uint32_t t = reachable; t != 0; t = (t - 1) & reachable)
    for (std::uint32_t st = t; st != 0; st = (st - 1) & t) {
      if (ContactSet::bitCount(st) < 2) continue;
      SupportStep held;
      if (!search_.stepTo(end, end.pose, ContactSet{t, st}, PivotAnchor{}, held)) continue;
      std::vector<SupportStep> run = rigidRun(held, theta);
      if (run.empty()) continue;
      double margin = held.margin;
      for (const SupportStep& w : run) margin = std::min(margin, w.margin);
      if (margin <= best_margin) continue;
      best_margin = margin;
      run.insert(run.begin(), held);
      best = std::move(run);
    }
  if (best.empty()) return {};
  out.insert(out.end(), best.begin(), best.end());
  return out;
}

}  // namespace rbsf::planner
