// SupportSearch::Run: the paths the search finds, where a start-tree node reaches the goal or
// a node of one tree reaches the other (support_search.h's file comment).
#include <algorithm>
#include <cmath>

#include "support_search_run.h"

namespace rbsf::planner {

void SupportSearch::Run::connectGoal() {
  const SupportStep& s = node_.step;
  order_.clear();
  for (int g = 0; g < static_cast<int>(goals_.size()); ++g)
    order_.emplace_back(poseDistance(s.pose, goals_[g], ls_), g);
  std::sort(order_.begin(), order_.end());
  std::vector<SupportStep> tail;
  if (s.set.phase() == Phase::kU) {
    for (const auto& [dist, g] : order_) {
      if (dist > settings_.goal_connect) break;
      if (!(tail = search_.straightSlide(s, goals_[g])).empty()) break;
    }
  } else if (s.set.pivot() >= 0) {
    double psi, th, l;
    if (pivotTarget(s, psi, th, l)) tail = search_.straightPivot(s, psi, th, l);
  }
  if (!tail.empty()) finish(id_, tail, -1);
}

void SupportSearch::Run::finish(int f, const std::vector<SupportStep>& middle, int b) {
  candidate_.clear();
  for (int n = f; n >= 0; n = trees_[0].nodes[n].parent)
    candidate_.push_back(trees_[0].nodes[n].step);
  std::reverse(candidate_.begin(), candidate_.end());
  candidate_.insert(candidate_.end(), middle.begin(), middle.end());
  for (int n = b >= 0 ? trees_[1].nodes[b].parent : -1; n >= 0; n = trees_[1].nodes[n].parent)
    candidate_.push_back(trees_[1].nodes[n].step);
  const int runs = phaseRuns(candidate_);
  const double length = pathLength(candidate_, ls_);
  if (!result_.found) {
    stop_at_ =
        result_.expansions +
        static_cast<long>(std::ceil(settings_.search_on * static_cast<double>(result_.expansions)));
  } else if (runs > best_runs_ || (runs == best_runs_ && length >= best_length_)) {
    return;
  }
  result_.found = true;
  result_.steps = candidate_;
  best_runs_ = runs;
  best_length_ = length;
}

bool SupportSearch::Run::meet(int t, int id) {
  const SupportStep& s = trees_[t].nodes[id].step;
  const auto it = trees_[1 - t].sliding.find(meetKey(s));
  if (it == trees_[1 - t].sliding.end()) return false;
  std::vector<std::pair<double, int>> near;
  for (int other : it->second) {
    const double dist = poseDistance(s.pose, trees_[1 - t].nodes[other].step.pose, ls_);
    if (dist <= settings_.goal_connect) near.emplace_back(dist, other);
  }
  std::sort(near.begin(), near.end());
  if (near.size() > 3) near.resize(3);
  for (const auto& [dist, other] : near) {
    const int f = t == 0 ? id : other, b = t == 0 ? other : id;
    const SupportStep& from = trees_[0].nodes[f].step;
    const SupportStep& to = trees_[1].nodes[b].step;
    if (from.set != to.set) continue;
    const std::vector<SupportStep> middle = search_.straightSlide(from, to.pose);
    if (middle.empty()) continue;
    finish(f, middle, b);
    return true;
  }
  return false;
}

bool SupportSearch::Run::meetPivot(int t, int id) {
  const SupportStep& s = trees_[t].nodes[id].step;
  std::vector<std::pair<double, int>> near;
  for (int j = 0; j < m_; ++j) {
    if (!s.set.touches(j) || j == s.set.pivot()) continue;
    for (int dp = -1; dp <= 1; ++dp)
      for (int dt = -1; dt <= 1; ++dt) {
        const auto it = trees_[1 - t].pivots.find(pivotKey(s, dp, dt, j));
        if (it == trees_[1 - t].pivots.end()) continue;
        for (int other : it->second)
          if (trees_[1 - t].nodes[other].step.set.touching == s.set.touching)
            near.emplace_back(poseDistance(s.pose, trees_[1 - t].nodes[other].step.pose, ls_),
                              other);
      }
  }
  std::sort(near.begin(), near.end());
  if (near.size() > 4) near.resize(4);
  for (const auto& [dist, other] : near) {
    const int f = t == 0 ? id : other, b = t == 0 ? other : id;
    const std::vector<SupportStep> middle =
        bridgePivots(trees_[0].nodes[f].step, trees_[1].nodes[b].step);
    if (middle.empty()) continue;
    finish(f, middle, b);
    return true;
  }
  return false;
}

std::vector<SupportStep> SupportSearch::Run::bridgePivots(const SupportStep& from,
                                                          const SupportStep& to) {
  // Pivot about k (base and stroke still) to the part angle where finger j's line enters
  // the part at to's anchor, switch the stick from k to j there, and pivot about j onto `to`
  // (its anchor then fixes the pose).
  std::vector<SupportStep> out;
  const double psi1 = handOverAngle(from, to);
  if (std::isnan(psi1)) return out;
  if (std::abs(psi1 - from.pose.psi) > 1e-12) {
    out = search_.straightPivot(from, psi1, from.pose.theta, from.anchor.stroke);
    if (out.empty()) return out;
  }
  const SupportStep& at = out.empty() ? from : out.back();
  PivotAnchor anchor;
  SupportStep handed;
  if (!search_.anchorFor(at.pose, to.set, anchor) ||
      !search_.stepTo(at, at.pose, to.set, anchor, handed))
    return std::vector<SupportStep>{};
  out.push_back(handed);
  const std::vector<SupportStep> last =
      search_.straightPivot(handed, to.pose.psi, to.pose.theta, to.anchor.stroke);
  if (last.empty()) return std::vector<SupportStep>{};
  out.insert(out.end(), last.begin(), last.end());
  return out;
}

double SupportSearch::Run::handOverAngle(const SupportStep& from, const SupportStep& to) {
  // Scanned in quarter steps for a sign change, then bisected: along the first pivot the
  // boundary parameter depends on the part angle alone.
  const double lo = std::min(from.pose.psi, to.pose.psi) - 2.0 * a_;
  const double hi = std::max(from.pose.psi, to.pose.psi) + 2.0 * a_;
  double psi1 = NAN, prev_psi = lo, prev = 0.0;
  bool have_prev = entryOffset(from, to, lo, prev);
  for (double psi = lo + 0.25 * a_; psi <= hi + 1e-12 && std::isnan(psi1); psi += 0.25 * a_) {
    double value;
    if (!entryOffset(from, to, psi, value)) {
      have_prev = false;
      continue;
    }
    if (have_prev && (prev <= 0.0) != (value <= 0.0) && std::abs(value - prev) < 1.0)
      psi1 = bisectHandOver(from, to, prev_psi, psi, prev);
    prev_psi = psi, prev = value, have_prev = true;
  }
  return psi1;
}

double SupportSearch::Run::bisectHandOver(const SupportStep& from, const SupportStep& to, double lo,
                                          double hi, double f_lo) {
  double l = lo, h = hi, fl = f_lo;
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (l + h);
    double fm;
    if (!entryOffset(from, to, mid, fm)) break;
    if ((fm <= 0.0) == (fl <= 0.0))
      l = mid, fl = fm;
    else
      h = mid;
  }
  return 0.5 * (l + h);
}

bool SupportSearch::Run::entryOffset(const SupportStep& from, const SupportStep& to, double psi,
                                     double& value) {
  const int j = to.set.pivot();
  const JigPose p = geometry_.pivotPose(from.anchor, psi, from.pose.theta);
  double stroke, xi;
  if (!geometry_.entry(p, j, stroke, xi, settings_.support.min_sticking_cosine)) return false;
  value = std::remainder(xi - to.anchor.xi, 2.0 * M_PI);
  return true;
}

}  // namespace rbsf::planner
