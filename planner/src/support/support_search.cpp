#include "rbsf/planner/support/support_search.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace rbsf::planner {

bool slidersSlip(const ContactSet& set, const VecC& slip) {
  for (int i = 0; i < slip.size(); ++i)
    if (set.touches(i) && !set.sticks(i) && std::abs(slip[i]) > kSlipStep) return true;
  return false;
}

double moveCost(const SupportStep& a, const SupportStep& b, const SupportSearchSettings& s) {
  return poseDistance(a.pose, b.pose, s.length_scale) *
         (1.0 + s.margin_weight / (std::min(a.margin, b.margin) + 0.01));
}

int phaseRuns(const std::vector<SupportStep>& steps) {
  int runs = 1;
  for (std::size_t k = 1; k < steps.size(); ++k) runs += steps[k].set != steps[k - 1].set ? 1 : 0;
  return runs;
}

double pathLength(const std::vector<SupportStep>& steps, double length_scale) {
  double length = 0.0;
  for (std::size_t k = 1; k < steps.size(); ++k)
    length += poseDistance(steps[k - 1].pose, steps[k].pose, length_scale);
  return length;
}

SupportSearch::SupportSearch(const RbsfModel& model, SupportSearchSettings settings)
    : model_(model), settings_(settings), geometry_(model, settings.support) {}

std::size_t SupportSearch::CellKeyHash::operator()(const CellKey& k) const {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the six numbers
  for (std::int32_t v : k) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
  return static_cast<std::size_t>(h);
}

SupportSearch::CellKey SupportSearch::key(const JigPose& pose, const ContactSet& set) const {
  auto idx = [](double v, double step) { return static_cast<std::int32_t>(std::lround(v / step)); };
  return CellKey{idx(pose.psi, settings_.angle_step),
                 idx(pose.theta, settings_.angle_step),
                 idx(pose.X, settings_.xy_step),
                 0,  // not Y: the height changes no balance (file comment)
                 static_cast<std::int32_t>(set.touching),
                 static_cast<std::int32_t>(set.sticking)};
}

void SupportSearch::block(const SupportStep& step, int radius) {
  const CellKey k = key(step.pose, step.set);
  for (int i = -radius; i <= radius; ++i)
    for (int j = -radius; j <= radius; ++j)
      for (int l = -radius; l <= radius; ++l)
        blocked_.insert(CellKey{k[0] + i, k[1] + j, k[2] + l, k[3], k[4], k[5]});
}

bool SupportSearch::anchorFor(const JigPose& pose, const ContactSet& set, PivotAnchor& anchor) {
  anchor = PivotAnchor{};
  const int k = set.pivot();
  if (k < 0) return true;
  anchor.finger = k;
  return geometry_.entry(pose, k, anchor.stroke, anchor.xi,
                         geometry_.settings().min_sticking_cosine);
}

bool SupportSearch::restAt(const JigPose& pose, const ContactSet& set, SupportStep& out) {
  if (!anchorFor(pose, set, out.anchor)) return false;
  const Support sup = geometry_.check(pose, set);
  if (!sup.valid) return false;
  out.pose = pose;
  out.set = set;
  out.q = sup.q;
  out.margin = sup.margin;
  out.rest = true;
  return true;
}

bool SupportSearch::stepTo(const SupportStep& from, const JigPose& pose, const ContactSet& set,
                           const PivotAnchor& anchor, SupportStep& out, bool backward) {
  if (!blocked_.empty() && blocked_.count(key(pose, set)) != 0) {
    refusal_ = SupportRule::kBlocked;
    return false;
  }
  const std::optional<VecQ> q = geometry_.configuration(pose, set, true, &refusal_);
  if (!q) return false;
  const VecC slip = set == from.set ? geometry_.slipDirections(from.q, *q) : VecC();
  const Support s = geometry_.balanceAt(*q, set, slip);
  if (!s.valid) {
    refusal_ = s.refusal;
    return false;
  }
  if (set == from.set && from.rest && !backward && settings_.support.require_breakaway &&
      !geometry_.breaksAway(from.q, set, slip)) {
    refusal_ = SupportRule::kBreakaway;
    return false;
  }
  if (set != from.set && !geometry_.handsOver(pose, from.set, from.q, set, s.q)) {
    refusal_ = SupportRule::kLaw;
    return false;
  }
  out.pose = pose;
  out.set = set;
  out.anchor = anchor;
  out.q = s.q;
  out.margin = s.margin;
  // Sliders that have not slipped yet are still stuck: the run starts at the first move that
  // slips one, and breakaway is checked there.
  const bool still = set == from.set && from.rest && !backward && !slidersSlip(set, slip);
  out.rest = set != from.set || still;
  return true;
}

std::vector<SupportStep> SupportSearch::straightSlide(const SupportStep& from, const JigPose& to) {
  const double span = std::max({std::abs(to.psi - from.pose.psi) / settings_.angle_step,
                                std::abs(to.theta - from.pose.theta) / settings_.angle_step,
                                std::abs(to.X - from.pose.X) / settings_.xy_step,
                                std::abs(to.Y - from.pose.Y) / settings_.xy_step});
  const int n = std::max(1, static_cast<int>(std::ceil(span)));
  std::vector<SupportStep> out;
  SupportStep prev = from, next;
  for (int k = 1; k <= n; ++k) {
    if (!stepTo(prev, lerpPose(from.pose, to, static_cast<double>(k) / n), from.set, from.anchor,
                next))
      return {};
    out.push_back(next);
    prev = next;
  }
  return out;
}

std::vector<SupportStep> SupportSearch::straightPivot(const SupportStep& from, double psi,
                                                      double theta, double stroke) {
  const double span = std::max({std::abs(psi - from.pose.psi) / settings_.angle_step,
                                std::abs(theta - from.pose.theta) / settings_.angle_step,
                                std::abs(stroke - from.anchor.stroke) / settings_.xy_step});
  const int n = std::max(1, static_cast<int>(std::ceil(span)));
  std::vector<SupportStep> out;
  SupportStep prev = from, next;
  for (int k = 1; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    PivotAnchor a = from.anchor;
    a.stroke += s * (stroke - from.anchor.stroke);
    const JigPose pose = geometry_.pivotPose(a, from.pose.psi + s * (psi - from.pose.psi),
                                             from.pose.theta + s * (theta - from.pose.theta));
    if (!stepTo(prev, pose, from.set, a, next)) return {};
    out.push_back(next);
    prev = next;
  }
  return out;
}

}  // namespace rbsf::planner
