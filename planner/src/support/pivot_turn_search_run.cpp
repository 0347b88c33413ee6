// PivotTurnSearch::Run: the leads, the lattice of each pivot finger and its expansion (moves,
// switches, the join to the goal) of the search of pivot_turn_search.h.
#include <algorithm>
#include <cmath>
#include <string>

#include "pivot_turn_search_run.h"

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

PivotTurnSearch::Run::Run(PivotTurnSearch& owner, const Pose& start, double start_theta,
                          const Pose& goal, const std::atomic<bool>* cancel)
    : owner_(owner),
      search_(owner.search_),
      settings_(owner.settings_),
      started_(Clock::now()),
      geometry_(owner.search_.geometry()),
      ss_(owner.search_.settings()),
      goal_(goal),
      cancel_(cancel),
      start_theta_(start_theta),
      a_(owner.settings_.angle_step),
      ds_(owner.settings_.stroke_step),
      ls_(ss_.length_scale),
      m_(geometry_.model().numFingers()),
      all_((1u << m_) - 1u),
      p0_(JigPose::fromWorld(start, start_theta)),
      placed_(geometry_.placedSet(p0_)),
      stop_at_(owner.settings_.max_expansions) {}

SupportPath PivotTurnSearch::Run::run() {
  collectLeads();
  for (int k = 0;
       k < m_ && !budget_out_ && !timed_out_ && !(result_.found && result_.expansions >= stop_at_);
       ++k) {
    if (!startPivot(k)) continue;
    seedPivot();
    if (!explorePivot()) return std::move(result_);
  }
  if (!result_.found)
    result_.message = timed_out_    ? "no simple turn within the time limit"
                      : budget_out_ ? "no simple turn within " +
                                          std::to_string(settings_.max_expansions) + " expansions"
                                    : "no pivot finger turns the part onto the goal in one pivot";
  return std::move(result_);
}

bool PivotTurnSearch::Run::root(const ContactSet& set, SupportStep& s) {
  if (!search_.anchorFor(p0_, set, s.anchor)) return false;
  const Support sup = geometry_.check(p0_, set);
  if (!sup.valid) return false;
  s.pose = p0_;
  s.set = set;
  s.q = sup.q;
  s.margin = sup.margin;
  s.rest = true;
  return true;
}

void PivotTurnSearch::Run::collectLeads() {
  leads_.assign(1, Lead());
  for (std::uint32_t t = placed_.touching; t != 0; t = (t - 1) & placed_.touching) {
    SupportStep r;
    if (ContactSet::bitCount(t) < 2 || !root(ContactSet{t, t}, r)) continue;
    leads_.push_back(Lead{{r}, 0.0});
    for (int dir : {1, -1}) rigidLeads(r, dir);
  }
}

void PivotTurnSearch::Run::rigidLeads(const SupportStep& r, int dir) {
  Lead lead{{r}, 0.0};
  for (int n = 1;; ++n) {
    JigPose pose = p0_;
    pose.theta = start_theta_ + dir * n * a_;
    SupportStep next;
    if (!search_.stepTo(lead.steps.back(), pose, r.set, PivotAnchor{}, next)) break;
    lead.g += moveCost(lead.steps.back(), next, ss_);
    lead.steps.push_back(next);
    leads_.push_back(lead);
  }
}

bool PivotTurnSearch::Run::startPivot(int k) {
  k_ = k;
  anchor_ = PivotAnchor();
  anchor_.finger = k;
  if (!placed_.touches(k) || !geometry_.entry(p0_, k, anchor_.stroke, anchor_.xi,
                                              geometry_.settings().min_sticking_cosine))
    return false;
  if (!geometry_.pivotOnto(anchor_, goal_, p0_.psi, psi_goal_, theta_goal_, l_goal_)) return false;
  touchings_.clear();
  for (std::uint32_t t = all_; t != 0; t = (t - 1) & all_)
    if (((t >> k) & 1u) != 0 && ContactSet::bitCount(t) >= 2) touchings_.push_back(t);
  nodes_.clear();
  best_.clear();
  open_ = decltype(open_)();
  return true;
}

void PivotTurnSearch::Run::seedPivot() {
  for (int li = 0; li < static_cast<int>(leads_.size()); ++li)
    for (std::uint32_t t : touchings_) {
      const ContactSet set{t, 1u << k_};
      Node node;
      node.lead = li;
      if (li == 0) {
        if (!root(set, node.step)) continue;
      } else {
        const SupportStep& from = leads_[li].steps.back();
        if (!search_.stepTo(from, from.pose, set, anchor_, node.step)) continue;
        node.g = leads_[li].g + ss_.switch_cost;
        node.j = static_cast<int>(std::lround((from.pose.theta - start_theta_) / a_));
      }
      push(node);
    }
}

double PivotTurnSearch::Run::heuristic(const SupportStep& s) const {
  return std::abs(s.pose.psi - psi_goal_) + std::abs(s.anchor.stroke - l_goal_) / ls_ +
         std::abs(s.pose.theta - theta_goal_);
}

void PivotTurnSearch::Run::push(const Node& node) {
  const std::uint64_t key = latticeKey(node.i, node.j, node.l, node.step.set.touching);
  const auto it = best_.find(key);
  if (it != best_.end() && it->second <= node.g + 1e-12) return;
  best_[key] = node.g;
  nodes_.push_back(node);
  open_.emplace(node.g + settings_.heuristic_weight * heuristic(node.step),
                static_cast<int>(nodes_.size()) - 1);
}

bool PivotTurnSearch::Run::explorePivot() {
  while (!open_.empty()) {
    if (!take()) continue;
    const Budget budget = spend();
    if (budget == Budget::kStop) break;
    if (budget == Budget::kCancel) return false;
    if (tryFinish()) break;  // the next pivot finger
    Node next;
    next.parent = id_;
    next.lead = node_.lead;
    latticeMoves(next);
    switches(next);
  }
  return true;
}

bool PivotTurnSearch::Run::take() {
  id_ = open_.top().second;
  open_.pop();
  node_ = nodes_[id_];
  const std::uint64_t key = latticeKey(node_.i, node_.j, node_.l, node_.step.set.touching);
  return !(best_[key] < node_.g - 1e-12);
}

PivotTurnSearch::Run::Budget PivotTurnSearch::Run::spend() {
  if (result_.found && result_.expansions >= stop_at_) return Budget::kStop;
  if (++result_.expansions > settings_.max_expansions) {
    budget_out_ = true;
    return Budget::kStop;
  }
  if ((result_.expansions & 255) == 0) {
    if (cancel_ != nullptr && cancel_->load()) {
      result_.message = "stopped";
      return Budget::kCancel;
    }
    if (std::chrono::duration<double>(Clock::now() - started_).count() > settings_.time_limit) {
      timed_out_ = true;
      return Budget::kStop;
    }
  }
  return Budget::kGoOn;
}

bool PivotTurnSearch::Run::tryFinish() {
  const SupportStep& s = node_.step;
  if (!(std::abs(s.pose.psi - psi_goal_) <= 0.5 * a_ + 1e-9 &&
        std::abs(s.anchor.stroke - l_goal_) <= 0.5 * ds_ + 1e-9))
    return false;
  const std::vector<SupportStep> tail = owner_.finish(s, psi_goal_, theta_goal_, l_goal_);
  if (tail.empty()) return false;
  keepPath(tail);
  return true;
}

void PivotTurnSearch::Run::keepPath(const std::vector<SupportStep>& tail) {
  std::vector<SupportStep> path;
  for (int n = id_; n >= 0; n = nodes_[n].parent) path.push_back(nodes_[n].step);
  const std::vector<SupportStep>& lead = leads_[node_.lead].steps;
  path.insert(path.end(), lead.rbegin(), lead.rend());
  std::reverse(path.begin(), path.end());
  path.insert(path.end(), tail.begin(), tail.end());
  const int runs = phaseRuns(path);
  const double length = pathLength(path, ls_);
  if (!result_.found)
    stop_at_ = std::min(
        settings_.max_expansions,
        result_.expansions + static_cast<long>(std::ceil(ss_.search_on * result_.expansions)));
  if (!result_.found || runs < best_runs_ || (runs == best_runs_ && length < best_length_)) {
    result_.found = true;
    result_.steps = std::move(path);
    best_runs_ = runs;
    best_length_ = length;
  }
}

void PivotTurnSearch::Run::latticeMoves(Node& next) {
  const SupportStep& s = node_.step;
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj)
      for (int dl = -1; dl <= 1; ++dl) {
        if (di == 0 && dj == 0 && dl == 0) continue;
        next.i = node_.i + di, next.j = node_.j + dj, next.l = node_.l + dl;
        PivotAnchor moved = s.anchor;
        moved.stroke = anchor_.stroke + next.l * ds_;
        const JigPose pose =
            geometry_.pivotPose(moved, p0_.psi + next.i * a_, start_theta_ + next.j * a_);
        if (!search_.stepTo(s, pose, s.set, moved, next.step)) continue;
        // A slider whose slip turns back sticks on the way: that is a rest, not a move.
        next.slip = geometry_.slipDirections(s.q, next.step.q);
        if (!s.rest && reverses(node_.slip, next.slip, s.set)) continue;
        next.g = node_.g + moveCost(s, next.step, ss_);
        push(next);
      }
}

void PivotTurnSearch::Run::switches(Node& next) {
  // At rest, fingers touch or let go; the pivot goes on about the same point.
  const SupportStep& s = node_.step;
  next.i = node_.i, next.j = node_.j, next.l = node_.l;
  next.slip = VecC();
  for (std::uint32_t t : touchings_) {
    if (t == s.set.touching) continue;
    if (!search_.stepTo(s, s.pose, ContactSet{t, 1u << k_}, s.anchor, next.step)) continue;
    next.g = node_.g + ss_.switch_cost;
    push(next);
  }
}

SupportPath PivotTurnSearch::search(const Pose& start, double start_theta, const Pose& goal,
                                    const std::atomic<bool>* cancel) {
  return Run(*this, start, start_theta, goal, cancel).run();
}

}  // namespace rbsf::planner
