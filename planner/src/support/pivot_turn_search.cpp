#include "rbsf/planner/support/pivot_turn_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>

namespace rbsf::planner {
namespace {

/// A lattice node of the pivot: (psi, theta, stroke) indices and the touching fingers.
std::uint64_t latticeKey(int i, int j, int l, std::uint32_t touching) {
  auto field = [](int v) { return static_cast<std::uint64_t>(v + 32768) & 0xffffu; };
  return (field(i) << 48) | (field(j) << 32) | (field(l) << 16) | (touching & 0xffffu);
}

/// Whether a sliding contact of `set` slips one way in `before` and the other in `after`
/// (each more than kSlipStep: a slider that barely moves does not turn back).
bool reverses(const VecC& before, const VecC& after, const ContactSet& set) {
  if (before.size() != after.size()) return false;
  for (int i = 0; i < before.size(); ++i)
    if (set.touches(i) && !set.sticks(i) && before[i] * after[i] < 0.0 &&
        std::abs(before[i]) > kSlipStep && std::abs(after[i]) > kSlipStep)
      return true;
  return false;
}

}  // namespace

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
  // At rest, two or more tips stick (the most first) and the base turns onto the goal.
  const std::uint32_t reachable =
      end.set.touching | search_.geometry().placedSet(end.pose).touching;
  std::vector<ContactSet> sets;
  for (std::uint32_t t = reachable; t != 0; t = (t - 1) & reachable)
    for (std::uint32_t st = t; st != 0; st = (st - 1) & t)
      if (ContactSet::bitCount(st) >= 2) sets.push_back(ContactSet{t, st});
  std::stable_sort(sets.begin(), sets.end(), [](const ContactSet& a, const ContactSet& b) {
    return a.stickingCount() > b.stickingCount();
  });
  for (const ContactSet& set : sets) {
    SupportStep held;
    if (!search_.stepTo(end, end.pose, set, PivotAnchor{}, held)) continue;
    const std::vector<SupportStep> run = rigidRun(held, theta);
    if (run.empty()) continue;
    out.push_back(held);
    out.insert(out.end(), run.begin(), run.end());
    return out;
  }
  return {};
}

SupportPath PivotTurnSearch::search(const Pose& start, double start_theta, const Pose& goal,
                                    const std::atomic<bool>* cancel) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point started = Clock::now();
  SupportPath result;
  SupportGeometry& geometry = search_.geometry();
  const SupportSearchSettings& ss = search_.settings();
  const double a = settings_.angle_step, ds = settings_.stroke_step, ls = ss.length_scale;
  const int m = geometry.model().numFingers();
  const std::uint32_t all = (1u << m) - 1u;
  const JigPose p0 = JigPose::fromWorld(start, start_theta);
  const ContactSet placed = geometry.placedSet(p0);

  // The part at rest on the start pose with `set`.
  auto root = [&](const ContactSet& set, SupportStep& s) {
    if (!search_.anchorFor(p0, set, s.anchor)) return false;
    const Support sup = geometry.check(p0, set);
    if (!sup.valid) return false;
    s.pose = p0;
    s.set = set;
    s.q = sup.q;
    s.margin = sup.margin;
    s.rest = true;
    return true;
  };
  // Where a pivot may start: the start itself (empty), or the end of a rigid run from it.
  struct Lead {
    std::vector<SupportStep> steps;
    double g = 0.0;
  };
  std::vector<Lead> leads(1);
  for (std::uint32_t t = placed.touching; t != 0; t = (t - 1) & placed.touching) {
    SupportStep r;
    if (ContactSet::bitCount(t) < 2 || !root(ContactSet{t, t}, r)) continue;
    leads.push_back(Lead{{r}, 0.0});
    for (int dir : {1, -1}) {
      Lead lead{{r}, 0.0};
      for (int n = 1;; ++n) {
        JigPose pose = p0;
        pose.theta = start_theta + dir * n * a;
        SupportStep next;
        if (!search_.stepTo(lead.steps.back(), pose, r.set, PivotAnchor{}, next)) break;
        lead.g += moveCost(lead.steps.back(), next, ss);
        lead.steps.push_back(next);
        leads.push_back(lead);
      }
    }
  }

  struct Node {
    SupportStep step;
    double g = 0.0;
    int parent = -1;
    int lead = 0;
    int i = 0, j = 0, l = 0;
    VecC slip;  ///< of the move that reached the node (empty at rest)
  };
  int best_runs = 0;
  double best_length = 0.0;
  bool budget_out = false, timed_out = false;
  long stop_at = settings_.max_expansions;  // after the first path: search_on times its cost
  for (int k = 0;
       k < m && !budget_out && !timed_out && !(result.found && result.expansions >= stop_at); ++k) {
    PivotAnchor anchor;
    anchor.finger = k;
    if (!placed.touches(k) ||
        !geometry.entry(p0, k, anchor.stroke, anchor.xi, geometry.settings().min_sticking_cosine))
      continue;
    double psi_goal, theta_goal, l_goal;
    if (!geometry.pivotOnto(anchor, goal, p0.psi, psi_goal, theta_goal, l_goal)) continue;
    std::vector<std::uint32_t> touchings;  // k and at least one slider
    for (std::uint32_t t = all; t != 0; t = (t - 1) & all)
      if (((t >> k) & 1u) != 0 && ContactSet::bitCount(t) >= 2) touchings.push_back(t);

    std::vector<Node> nodes;
    std::unordered_map<std::uint64_t, double> best;
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    auto heuristic = [&](const SupportStep& s) {
      return std::abs(s.pose.psi - psi_goal) + std::abs(s.anchor.stroke - l_goal) / ls +
             std::abs(s.pose.theta - theta_goal);
    };
    auto push = [&](const Node& node) {
      const std::uint64_t key = latticeKey(node.i, node.j, node.l, node.step.set.touching);
      const auto it = best.find(key);
      if (it != best.end() && it->second <= node.g + 1e-12) return;
      best[key] = node.g;
      nodes.push_back(node);
      open.emplace(node.g + settings_.heuristic_weight * heuristic(node.step),
                   static_cast<int>(nodes.size()) - 1);
    };
    for (int li = 0; li < static_cast<int>(leads.size()); ++li)
      for (std::uint32_t t : touchings) {
        const ContactSet set{t, 1u << k};
        Node node;
        node.lead = li;
        if (li == 0) {
          if (!root(set, node.step)) continue;
        } else {
          const SupportStep& from = leads[li].steps.back();
          if (!search_.stepTo(from, from.pose, set, anchor, node.step)) continue;
          node.g = leads[li].g + ss.switch_cost;
          node.j = static_cast<int>(std::lround((from.pose.theta - start_theta) / a));
        }
        push(node);
      }

    while (!open.empty()) {
      const int id = open.top().second;
      open.pop();
      const Node node = nodes[id];
      const std::uint64_t key = latticeKey(node.i, node.j, node.l, node.step.set.touching);
      if (best[key] < node.g - 1e-12) continue;
      if (result.found && result.expansions >= stop_at) break;
      if (++result.expansions > settings_.max_expansions) {
        budget_out = true;
        break;
      }
      if ((result.expansions & 255) == 0) {
        if (cancel != nullptr && cancel->load()) {
          result.message = "stopped";
          return result;
        }
        if (std::chrono::duration<double>(Clock::now() - started).count() > settings_.time_limit) {
          timed_out = true;
          break;
        }
      }
      const SupportStep& s = node.step;
      if (std::abs(s.pose.psi - psi_goal) <= 0.5 * a + 1e-9 &&
          std::abs(s.anchor.stroke - l_goal) <= 0.5 * ds + 1e-9) {
        const std::vector<SupportStep> tail = finish(s, psi_goal, theta_goal, l_goal);
        if (!tail.empty()) {
          std::vector<SupportStep> path;
          for (int n = id; n >= 0; n = nodes[n].parent) path.push_back(nodes[n].step);
          const std::vector<SupportStep>& lead = leads[node.lead].steps;
          path.insert(path.end(), lead.rbegin(), lead.rend());
          std::reverse(path.begin(), path.end());
          path.insert(path.end(), tail.begin(), tail.end());
          const int runs = phaseRuns(path);
          const double length = pathLength(path, ls);
          if (!result.found)
            stop_at = std::min(
                settings_.max_expansions,
                result.expansions + static_cast<long>(std::ceil(ss.search_on * result.expansions)));
          if (!result.found || runs < best_runs || (runs == best_runs && length < best_length)) {
            result.found = true;
            result.steps = std::move(path);
            best_runs = runs;
            best_length = length;
          }
          break;  // the next pivot finger
        }
      }
      Node next;
      next.parent = id;
      next.lead = node.lead;
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj)
          for (int dl = -1; dl <= 1; ++dl) {
            if (di == 0 && dj == 0 && dl == 0) continue;
            next.i = node.i + di, next.j = node.j + dj, next.l = node.l + dl;
            PivotAnchor moved = s.anchor;
            moved.stroke = anchor.stroke + next.l * ds;
            const JigPose pose =
                geometry.pivotPose(moved, p0.psi + next.i * a, start_theta + next.j * a);
            if (!search_.stepTo(s, pose, s.set, moved, next.step)) continue;
            // A slider whose slip turns back sticks on the way: that is a rest, not a move.
            next.slip = geometry.slipDirections(s.q, next.step.q);
            if (!s.rest && reverses(node.slip, next.slip, s.set)) continue;
            next.g = node.g + moveCost(s, next.step, ss);
            push(next);
          }
      // At rest, fingers touch or let go; the pivot goes on about the same point.
      next.i = node.i, next.j = node.j, next.l = node.l;
      next.slip = VecC();
      for (std::uint32_t t : touchings) {
        if (t == s.set.touching) continue;
        if (!search_.stepTo(s, s.pose, ContactSet{t, 1u << k}, s.anchor, next.step)) continue;
        next.g = node.g + ss.switch_cost;
        push(next);
      }
    }
  }
  if (!result.found)
    result.message = timed_out    ? "no simple turn within the time limit"
                     : budget_out ? "no simple turn within " +
                                        std::to_string(settings_.max_expansions) + " expansions"
                                  : "no pivot finger turns the part onto the goal in one pivot";
  return result;
}

}  // namespace rbsf::planner
