#include "rbsf/planner/support_search.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>

namespace rbsf::planner {
namespace {

JigPose lerp(const JigPose& a, const JigPose& b, double s) {
  return JigPose{a.X + s * (b.X - a.X), a.Y + s * (b.Y - a.Y), a.psi + s * (b.psi - a.psi),
                 a.theta + s * (b.theta - a.theta)};
}

}  // namespace

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

struct SupportSearch::Node {
  SupportStep step;
  double g = 0.0;
  int parent = -1;
  double h = 0.0;  ///< the tree's heuristic at the node (start tree: to the goal)
};

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
    if (!stepTo(prev, lerp(from.pose, to, static_cast<double>(k) / n), from.set, from.anchor, next))
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

SupportPath SupportSearch::search(const Pose& start, double start_theta, const Pose& goal,
                                  const std::atomic<bool>* cancel) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point started = Clock::now();
  SupportPath result;
  const double a = settings_.angle_step, d = settings_.xy_step, ls = settings_.length_scale;
  const int m = model_.numFingers();
  const Cell& cell = model_.cell();

  // Goal candidates: the goal pose seen from base angles across the range.
  std::vector<JigPose> goals;
  const double t_lo = cell.base.theta_min + settings_.support.theta_margin;
  const double t_hi = cell.base.theta_max - settings_.support.theta_margin;
  for (double th = t_lo; th <= t_hi + 1e-12; th += settings_.goal_theta_step)
    for (int turn = -1; turn <= 1; ++turn) {
      JigPose g = JigPose::fromWorld(goal, th);
      g.psi += 2.0 * M_PI * turn;
      if (std::abs(g.psi) <= 2.0 * M_PI + 1e-9) goals.push_back(g);
    }
  auto poseHeuristic = [&](const JigPose& p) {
    double h = INFINITY;
    for (const JigPose& g : goals) h = std::min(h, poseDistance(p, g, ls));
    return h;
  };
  // The pivot that puts the part on the goal (SupportGeometry::pivotOnto).
  auto pivotTarget = [&](const SupportStep& s, double& psi, double& th, double& l) {
    return geometry_.pivotOnto(s.anchor, goal, s.pose.psi, psi, th, l);
  };
  // `h` is poseHeuristic(s.pose), which the caller has at hand.
  auto heuristic = [&](const SupportStep& s, double h) {
    if (s.set.pivot() < 0) return h;
    double psi, th, l;
    if (!pivotTarget(s, psi, th, l)) return h + 2.0 * settings_.switch_cost;
    return std::min(h, std::abs(psi - s.pose.psi) + std::abs(th - s.pose.theta) +
                           std::abs(l - s.anchor.stroke) / ls);
  };

  // Pivots meet by part and base angle, touching fingers and pivot finger.
  auto pivotKey = [&](const SupportStep& s, int dpsi, int dtheta, int finger) {
    return CellKey{static_cast<std::int32_t>(std::lround(s.pose.psi / a)) + dpsi,
                   static_cast<std::int32_t>(std::lround(s.pose.theta / a)) + dtheta,
                   finger,
                   0,
                   static_cast<std::int32_t>(s.set.touching),
                   0};
  };
  // Sliding nodes meet by part angle and touching fingers.
  auto meetKey = [&](const SupportStep& s) {
    return CellKey{static_cast<std::int32_t>(std::lround(s.pose.psi / a)),
                   0,
                   0,
                   0,
                   static_cast<std::int32_t>(s.set.touching),
                   0};
  };
  // Two trees: from the start (forward) and from the goal's supports (backward); quasi-static
  // moves are reversible, so a backward chain read from a node to its root runs to the goal.
  using Entry = std::pair<double, int>;
  struct Tree {
    std::vector<Node> nodes;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    std::unordered_map<CellKey, double, CellKeyHash> best;
    std::unordered_map<CellKey, std::vector<int>, CellKeyHash> sliding;  // U nodes by cell
    std::unordered_map<CellKey, std::vector<int>, CellKeyHash> pivots;   // P nodes by cell
  };
  Tree trees[2];
  const JigPose start_pose = JigPose::fromWorld(start, start_theta);
  SupportReach& reach = result.reach;
  reach.measured = true;
  reach.psi_min = reach.psi_max = start_pose.psi;
  reach.phi_min = reach.phi_max = start.phi;
  reach.closest = start;
  reach.closest_score = INFINITY;
  // The start tree's reach: angle ranges and the pose closest to the goal.
  auto noteReached = [&](const SupportStep& s, double score) {
    const Pose w = s.pose.world();
    reach.psi_min = std::min(reach.psi_min, s.pose.psi);
    reach.psi_max = std::max(reach.psi_max, s.pose.psi);
    reach.phi_min = std::min(reach.phi_min, w.phi);
    reach.phi_max = std::max(reach.phi_max, w.phi);
    ++reach.poses;
    if (score < reach.closest_score) {
      reach.closest_score = score;
      reach.closest = w;
      reach.closest_position = std::hypot(goal.x - w.x, goal.y - w.y);
      reach.closest_angle = std::remainder(goal.phi - w.phi, 2.0 * M_PI);
    }
  };
  auto push = [&](int t, const SupportStep& s, double g, int parent) {
    Tree& tree = trees[t];
    const CellKey k = key(s.pose, s.set);
    if (blocked_.count(k) != 0) return;
    const auto it = tree.best.find(k);
    if (it != tree.best.end() && it->second <= g + 1e-12) return;
    tree.best[k] = g;
    double h = poseDistance(s.pose, start_pose, ls);  // the goal tree grows towards the start
    if (t == 0) {
      const double to_goal = poseHeuristic(s.pose);
      h = heuristic(s, to_goal);
      noteReached(s, to_goal);
    }
    tree.nodes.push_back(Node{s, g, parent, h});
    const int id = static_cast<int>(tree.nodes.size()) - 1;
    tree.open.emplace(g + settings_.heuristic_weight * h, id);
    if (s.set.phase() == Phase::kU) tree.sliding[meetKey(s)].push_back(id);
    if (s.set.phase() == Phase::kP) tree.pivots[pivotKey(s, 0, 0, s.set.pivot())].push_back(id);
  };
  // Roots: every valid set of the placement rule's fingers at the start, and at the goal seen
  // from each candidate base angle.
  auto seed = [&](int t, const JigPose& pose) {
    const ContactSet placed = geometry_.placedSet(pose);
    // At rest any of the placed fingers may let go, and any of the others stick.
    std::vector<ContactSet> sets;
    for (std::uint32_t touch = placed.touching; touch != 0; touch = (touch - 1) & placed.touching)
      for (std::uint32_t st = touch;; st = (st - 1) & touch) {
        sets.push_back(ContactSet{touch, st});
        if (st == 0) break;
      }
    for (const ContactSet& set : sets) {
      SupportStep s;
      if (!anchorFor(pose, set, s.anchor)) continue;
      const Support sup = geometry_.check(pose, set);
      if (!sup.valid) continue;
      s.pose = pose;
      s.set = set;
      s.q = sup.q;
      s.margin = sup.margin;
      s.rest = true;
      push(t, s, 0.0, -1);
    }
  };
  seed(0, start_pose);
  if (trees[0].nodes.empty()) {
    result.message = "the start support is not in balance with the required margins";
    return result;
  }
  for (const JigPose& g : goals) seed(1, g);

  // A path: the forward chain to `f`, `middle`, then the backward chain from `b` (if any).
  // The first one found sets how long the search goes on (search_on); of those found, the
  // one with the fewest phase runs, then the shortest, is kept.
  long stop_at = 0;
  int best_runs = 0;
  double best_length = 0.0;
  std::vector<SupportStep> candidate;
  auto finish = [&](int f, const std::vector<SupportStep>& middle, int b) {
    candidate.clear();
    for (int n = f; n >= 0; n = trees[0].nodes[n].parent)
      candidate.push_back(trees[0].nodes[n].step);
    std::reverse(candidate.begin(), candidate.end());
    candidate.insert(candidate.end(), middle.begin(), middle.end());
    for (int n = b >= 0 ? trees[1].nodes[b].parent : -1; n >= 0; n = trees[1].nodes[n].parent)
      candidate.push_back(trees[1].nodes[n].step);
    const int runs = phaseRuns(candidate);
    const double length = pathLength(candidate, ls);
    if (!result.found) {
      stop_at = result.expansions +
                static_cast<long>(
                    std::ceil(settings_.search_on * static_cast<double>(result.expansions)));
    } else if (runs > best_runs || (runs == best_runs && length >= best_length)) {
      return;
    }
    result.found = true;
    result.steps = candidate;
    best_runs = runs;
    best_length = length;
  };

  // A new sliding node of tree t meets the other tree's sliding nodes in its cell.
  auto meet = [&](int t, int id) {
    const SupportStep& s = trees[t].nodes[id].step;
    const auto it = trees[1 - t].sliding.find(meetKey(s));
    if (it == trees[1 - t].sliding.end()) return false;
    std::vector<std::pair<double, int>> near;
    for (int other : it->second) {
      const double dist = poseDistance(s.pose, trees[1 - t].nodes[other].step.pose, ls);
      if (dist <= settings_.goal_connect) near.emplace_back(dist, other);
    }
    std::sort(near.begin(), near.end());
    if (near.size() > 3) near.resize(3);
    for (const auto& [dist, other] : near) {
      const int f = t == 0 ? id : other, b = t == 0 ? other : id;
      const SupportStep& from = trees[0].nodes[f].step;
      const SupportStep& to = trees[1].nodes[b].step;
      if (from.set != to.set) continue;
      const std::vector<SupportStep> middle = straightSlide(from, to.pose);
      if (middle.empty()) continue;
      finish(f, middle, b);
      return true;
    }
    return false;
  };

  // Two pivots on fingers k (from) and j (to) with the same touching fingers: pivot about k
  // (base and stroke still) to the part angle where finger j's line enters the part at
  // to's anchor, switch the stick from k to j there, and pivot about j onto `to` (its
  // anchor then fixes the pose). The part angle is found by bisection on the boundary
  // parameter, which along the first pivot depends on the part angle alone.
  auto bridgePivots = [&](const SupportStep& from, const SupportStep& to) {
    std::vector<SupportStep> out;
    const int j = to.set.pivot();
    auto offset = [&](double psi, double& value) {
      const JigPose p = geometry_.pivotPose(from.anchor, psi, from.pose.theta);
      double stroke, xi;
      if (!geometry_.entry(p, j, stroke, xi, settings_.support.min_sticking_cosine)) return false;
      value = std::remainder(xi - to.anchor.xi, 2.0 * M_PI);
      return true;
    };
    const double lo = std::min(from.pose.psi, to.pose.psi) - 2.0 * a;
    const double hi = std::max(from.pose.psi, to.pose.psi) + 2.0 * a;
    double psi1 = NAN, prev_psi = lo, prev = 0.0;
    bool have_prev = offset(lo, prev);
    for (double psi = lo + 0.25 * a; psi <= hi + 1e-12 && std::isnan(psi1); psi += 0.25 * a) {
      double value;
      if (!offset(psi, value)) {
        have_prev = false;
        continue;
      }
      if (have_prev && (prev <= 0.0) != (value <= 0.0) && std::abs(value - prev) < 1.0) {
        double l = prev_psi, h = psi, fl = prev;
        for (int it = 0; it < 50; ++it) {
          const double mid = 0.5 * (l + h);
          double fm;
          if (!offset(mid, fm)) break;
          if ((fm <= 0.0) == (fl <= 0.0))
            l = mid, fl = fm;
          else
            h = mid;
        }
        psi1 = 0.5 * (l + h);
      }
      prev_psi = psi, prev = value, have_prev = true;
    }
    if (std::isnan(psi1)) return out;
    if (std::abs(psi1 - from.pose.psi) > 1e-12) {
      out = straightPivot(from, psi1, from.pose.theta, from.anchor.stroke);
      if (out.empty()) return out;
    }
    const SupportStep& at = out.empty() ? from : out.back();
    PivotAnchor anchor;
    SupportStep handed;
    if (!anchorFor(at.pose, to.set, anchor) || !stepTo(at, at.pose, to.set, anchor, handed))
      return std::vector<SupportStep>{};
    out.push_back(handed);
    const std::vector<SupportStep> last =
        straightPivot(handed, to.pose.psi, to.pose.theta, to.anchor.stroke);
    if (last.empty()) return std::vector<SupportStep>{};
    out.insert(out.end(), last.begin(), last.end());
    return out;
  };
  // A new pivot node of tree t meets the other tree's pivots on another finger nearby.
  auto meetPivot = [&](int t, int id) {
    const SupportStep& s = trees[t].nodes[id].step;
    std::vector<std::pair<double, int>> near;
    for (int j = 0; j < m; ++j) {
      if (!s.set.touches(j) || j == s.set.pivot()) continue;
      for (int dp = -1; dp <= 1; ++dp)
        for (int dt = -1; dt <= 1; ++dt) {
          const auto it = trees[1 - t].pivots.find(pivotKey(s, dp, dt, j));
          if (it == trees[1 - t].pivots.end()) continue;
          for (int other : it->second)
            if (trees[1 - t].nodes[other].step.set.touching == s.set.touching)
              near.emplace_back(poseDistance(s.pose, trees[1 - t].nodes[other].step.pose, ls),
                                other);
        }
    }
    std::sort(near.begin(), near.end());
    if (near.size() > 4) near.resize(4);
    for (const auto& [dist, other] : near) {
      const int f = t == 0 ? id : other, b = t == 0 ? other : id;
      const std::vector<SupportStep> middle =
          bridgePivots(trees[0].nodes[f].step, trees[1].nodes[b].step);
      if (middle.empty()) continue;
      finish(f, middle, b);
      return true;
    }
    return false;
  };

  std::vector<std::pair<double, int>> order;
  int turn = 1;
  while (!trees[0].open.empty() || !trees[1].open.empty()) {
    turn = trees[1 - turn].open.empty() ? turn : 1 - turn;
    const int t = turn;
    Tree& tree = trees[t];
    // A plain variable: lambdas below capture it, which clang 14 refuses for bindings.
    const int id = tree.open.top().second;
    tree.open.pop();
    const Node node = tree.nodes[id];
    if (tree.best[key(node.step.pose, node.step.set)] < node.g - 1e-12) continue;
    if (result.found && result.expansions >= stop_at) break;
    if (++result.expansions > settings_.max_expansions) break;
    if ((result.expansions & 255) == 0) {
      if (cancel != nullptr && cancel->load()) {
        result.message = "stopped";
        return result;
      }
      if (std::chrono::duration<double>(Clock::now() - started).count() > settings_.time_limit) {
        if (result.found) break;
        result.message = "no support path within the time limit";
        return result;
      }
    }
    const SupportStep& s = node.step;

    if (t == 0 && node.h <= settings_.goal_connect) {
      order.clear();
      for (int g = 0; g < static_cast<int>(goals.size()); ++g)
        order.emplace_back(poseDistance(s.pose, goals[g], ls), g);
      std::sort(order.begin(), order.end());
      std::vector<SupportStep> tail;
      if (s.set.phase() == Phase::kU) {
        for (const auto& [dist, g] : order) {
          if (dist > settings_.goal_connect) break;
          if (!(tail = straightSlide(s, goals[g])).empty()) break;
        }
      } else if (s.set.pivot() >= 0) {
        double psi, th, l;
        if (pivotTarget(s, psi, th, l)) tail = straightPivot(s, psi, th, l);
      }
      if (!tail.empty()) finish(id, tail, -1);
    }

    SupportStep next;
    auto add = [&](double g) {
      const std::size_t before = tree.nodes.size();
      push(t, next, g, id);
      if (tree.nodes.size() <= before) return;
      const int added = static_cast<int>(tree.nodes.size()) - 1;
      if (next.set.phase() == Phase::kU)
        meet(t, added);
      else if (next.set.phase() == Phase::kP)
        meetPivot(t, added);
    };
    // A refused start-tree move that would have gone beyond the closest pose counts
    // against the rule it broke (the reachability answer).
    auto refused = [&](const JigPose& pose) {
      if (t == 0 && poseHeuristic(pose) < reach.closest_score)
        ++reach.refused[static_cast<int>(refusal_)];
    };
    auto tryMove = [&](const JigPose& pose, const ContactSet& set, const PivotAnchor& anchor) {
      SupportStep mid;
      if (!stepTo(s, lerp(s.pose, pose, 0.5), set, anchor, mid, t == 1) ||
          !stepTo(mid, pose, set, anchor, next, t == 1)) {
        refused(pose);
        return;
      }
      add(node.g + moveCost(s, next, settings_));
    };
    // In the goal tree a switch away from s starts (in time) the run from s towards the
    // node s came from: its sliders must break away there.
    bool can_leave = true;
    if (t == 1 && node.parent >= 0 && settings_.support.require_breakaway) {
      const SupportStep& towards = tree.nodes[node.parent].step;
      if (towards.set == s.set)
        can_leave = geometry_.breaksAway(s.q, s.set, geometry_.slipDirections(s.q, towards.q));
    }
    auto trySwitch = [&](const ContactSet& set) {
      PivotAnchor anchor;
      if (!can_leave || !anchorFor(s.pose, set, anchor)) return;
      if (set.pivot() >= 0 && set.pivot() == s.set.pivot()) anchor = s.anchor;
      if (stepTo(s, s.pose, set, anchor, next)) add(node.g + settings_.switch_cost);
    };

    const std::uint32_t touching = s.set.touching;
    switch (s.set.phase()) {
      case Phase::kU: {
        static const int kMoves[][4] = {{1, 0, 0, 0}, {-1, 0, 0, 0}, {0, 1, 0, 0},  {0, -1, 0, 0},
                                        {0, 0, 1, 0}, {0, 0, -1, 0}, {0, 0, 0, 1},  {0, 0, 0, -1},
                                        {0, 0, 1, 1}, {0, 0, 1, -1}, {0, 0, -1, 1}, {0, 0, -1, -1},
                                        {1, 0, 1, 0}, {1, 0, -1, 0}, {-1, 0, 1, 0}, {-1, 0, -1, 0}};
        for (const auto& mv : kMoves)
          tryMove(JigPose{s.pose.X + mv[0] * d, s.pose.Y + mv[1] * d, s.pose.psi + mv[2] * a,
                          s.pose.theta + mv[3] * a},
                  s.set, s.anchor);
        break;
      }
      case Phase::kP: {
        static const int kMoves[][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},  {0, -1, 0},
                                        {1, 1, 0}, {1, -1, 0}, {-1, 1, 0}, {-1, -1, 0},
                                        {0, 0, 1}, {0, 0, -1}};
        for (const auto& mv : kMoves) {
          PivotAnchor anchor = s.anchor;
          anchor.stroke += mv[2] * d;
          tryMove(geometry_.pivotPose(anchor, s.pose.psi + mv[0] * a, s.pose.theta + mv[1] * a),
                  s.set, anchor);
        }
        break;
      }
      default: {  // rigid with the base: the base turns, or every finger strokes alike
        static const int kMoves[][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        for (const auto& mv : kMoves)
          tryMove(JigPose{s.pose.X, s.pose.Y + mv[1] * d, s.pose.psi, s.pose.theta + mv[0] * a},
                  s.set, s.anchor);
        break;
      }
    }
    // Switches at this pose: every contact slides, one sticks, all stick; a finger touches
    // (sliding, or sticking beside a sticking one) or lets go (a sliding one, or a sticking
    // one beside another).
    if (s.set.sticking != 0) trySwitch(ContactSet{touching, 0u});
    for (int k = 0; k < m; ++k)
      if ((touching >> k) & 1u && s.set.sticking != (1u << k))
        trySwitch(ContactSet{touching, 1u << k});
    if (s.set.sticking != touching) trySwitch(ContactSet{touching, touching});
    for (int j = 0; j < m; ++j) {
      const std::uint32_t bit = 1u << j;
      if (!s.set.sticks(j)) trySwitch(ContactSet{touching ^ bit, s.set.sticking});
      if (s.set.sticks(j) && s.set.stickingCount() > 1)
        trySwitch(ContactSet{touching & ~bit, s.set.sticking & ~bit});  // a sticking one lets go
      if (!s.set.touches(j) && s.set.sticking != 0)
        trySwitch(ContactSet{touching | bit, s.set.sticking | bit});  // placed to stick
    }
  }
  if (!result.found && result.message.empty())
    result.message =
        result.expansions > settings_.max_expansions
            ? "no support path within " + std::to_string(settings_.max_expansions) + " expansions"
            : "both trees were searched out without meeting (at this resolution and these margins)";
  return result;
}

}  // namespace rbsf::planner
