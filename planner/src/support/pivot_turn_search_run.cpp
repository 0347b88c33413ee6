// PivotTurnSearch::Run: the lattice of simple turns, deepened one pivot at a time, and its
// expansion (pivot and rigid moves, switches at rest, the join to the goal) of the search of
// pivot_turn_search.h.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "pivot_turn_search_run.h"

namespace rbsf::planner {
namespace {

/// Whether a sliding contact of `set` slips one way in `before` and the other in `after`
/// (each more than kSlipStep: a slider that barely moves does not turn back).
/// A slider slips at least this much in each move of a pivot [m]: one whose slip passes
/// through zero inside a run sticks there, and the law must pull it loose again mid-run.
constexpr double kRunSlip = 1e-3;

/// Whether every sliding contact of `set` slips at least kRunSlip in `slip`.
bool slidersKeepSliding(const VecC& slip, const ContactSet& set) {
  for (int i = 0; i < slip.size(); ++i)
    if (set.touches(i) && !set.sticks(i) && std::abs(slip[i]) < kRunSlip) return false;
  return true;
}

bool reverses(const VecC& before, const VecC& after, const ContactSet& set) {
  if (before.size() != after.size()) return false;
  for (int i = 0; i < before.size(); ++i)
    if (set.touches(i) && !set.sticks(i) && before[i] * after[i] < 0.0 &&
        std::abs(before[i]) > kSlipStep && std::abs(after[i]) > kSlipStep)
      return true;
  return false;
}

}  // namespace

std::size_t PivotTurnSearch::Run::CellKeyHash::operator()(const CellKey& k) const {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the seven numbers
  for (std::int32_t v : k) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
  return static_cast<std::size_t>(h);
}

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
      p0_(JigPose::fromWorld(start, start_theta)),
      stop_at_(owner.settings_.max_expansions) {}

SupportPath PivotTurnSearch::Run::run() {
  // A goal that no finger holds at any base angle cannot end a pivot: no search.
  bool held = false;
  const Cell& cell = geometry_.model().cell();
  const SupportSettings& gs = geometry_.settings();
  for (double th = cell.base.theta_min; th <= cell.base.theta_max && !held; th += 0.5 * a_)
    for (int k = 0; k < m_ && !held; ++k) {
      double l = 0.0, xi = 0.0;
      const FingerParams& f = cell.fingers[k];
      held = geometry_.entry(JigPose::fromWorld(goal_, th), k, l, xi, gs.min_sticking_cosine) &&
             l >= f.stroke_min + gs.stroke_margin && l <= f.stroke_max - gs.stroke_margin;
    }
  if (!held) {
    result_.message = "no pivot finger holds the part on the goal at any base angle";
    return std::move(result_);
  }
  for (int depth = 1; depth <= settings_.max_pivots && !result_.found; ++depth)
    if (!explore(depth) || budget_out_ || timed_out_) break;
  if (!result_.found && result_.message.empty())
    result_.message =
        timed_out_ ? "no simple turn within the time limit"
        : budget_out_
            ? "no simple turn within " + std::to_string(settings_.max_expansions) + " expansions"
            : "no simple turn of at most " + std::to_string(settings_.max_pivots) + " pivots";
  return std::move(result_);
}

std::vector<ContactSet> PivotTurnSearch::Run::restSets(const JigPose& pose,
                                                       std::uint32_t touching) const {
  return restSetsWithin(touching | geometry_.placedSet(pose).touching, m_, settings_.max_sliders);
}

void PivotTurnSearch::Run::seed() {
  // The part is placed on every finger that reaches it; a root that lifts some pays their
  // travel, as a switch does.
  const ContactSet placed = geometry_.placedSet(p0_);
  const std::optional<VecQ> q_placed =
      geometry_.configuration(p0_, ContactSet{placed.touching, placed.touching}, false);
  for (const ContactSet& set : restSets(p0_, placed.touching)) {
    Node node;
    node.pivots = set.pivot() >= 0 ? 1 : 0;
    if (!search_.restAt(p0_, set, node.step)) continue;
    if (q_placed) node.g = strokeTravel(*q_placed, node.step.q);
    push(node);
  }
}

PivotTurnSearch::Run::CellKey PivotTurnSearch::Run::key(const Node& node) const {
  const JigPose& p = node.step.pose;
  auto idx = [](double v, double step) { return static_cast<std::int32_t>(std::lround(v / step)); };
  return CellKey{idx(p.psi - p0_.psi, a_),
                 idx(p.theta - start_theta_, a_),
                 idx(p.X, settings_.xy_step),
                 idx(p.Y, settings_.xy_step),
                 static_cast<std::int32_t>(node.step.set.touching),
                 static_cast<std::int32_t>(node.step.set.sticking),
                 node.pivots};
}

double PivotTurnSearch::Run::strokeTravel(const VecQ& a, const VecQ& b) const {
  return (b - a).tail(m_).cwiseAbs().sum() / ls_;
}

double PivotTurnSearch::Run::heuristic(const SupportStep& s) const {
  // A pivot whose anchor can put the part on the goal: the way to that pivot's end.
  double psi = 0.0, theta = 0.0, l = 0.0;
  if (s.set.pivot() >= 0 && geometry_.pivotOnto(s.anchor, goal_, s.pose.psi, psi, theta, l))
    return std::abs(s.pose.psi - psi) + std::abs(s.anchor.stroke - l) / ls_ +
           std::abs(s.pose.theta - theta);
  // Else another pivot first, and the world pose to cover.
  const Pose w = s.pose.world();
  return settings_.pivot_cost + std::abs(w.phi - goal_.phi) +
         std::hypot(w.x - goal_.x, w.y - goal_.y) / ls_;
}

void PivotTurnSearch::Run::push(const Node& node) {
  const CellKey k = key(node);
  const auto it = best_.find(k);
  if (it != best_.end() && it->second <= node.g + 1e-12) return;
  best_[k] = node.g;
  nodes_.push_back(node);
  open_.emplace(node.g + settings_.heuristic_weight * heuristic(node.step),
                static_cast<int>(nodes_.size()) - 1);
}

bool PivotTurnSearch::Run::explore(int depth) {
  nodes_.clear();
  best_.clear();
  open_ = decltype(open_)();
  seed();
  while (!open_.empty()) {
    if (!take()) continue;
    if (node_.pivots > depth) continue;
    const Budget budget = spend();
    if (budget == Budget::kStop) break;
    if (budget == Budget::kCancel) return false;
    if (tryFinish()) continue;
    Node next;
    next.parent = id_;
    if (node_.step.set.pivot() >= 0)
      pivotMoves(next);
    else if (node_.step.set.stickingCount() >= 2)
      rigidMoves(next);
    switches(next, depth);
  }
  return true;
}

bool PivotTurnSearch::Run::take() {
  id_ = open_.top().second;
  open_.pop();
  node_ = nodes_[id_];
  return !(best_[key(node_)] < node_.g - 1e-12);
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

bool PivotTurnSearch::Run::keepsWay(const std::array<int, 3>& dir, const std::array<int, 3>& d,
                                    std::array<int, 3>& out) {
  for (int c = 0; c < 3; ++c) {
    if (d[c] != 0 && dir[c] != 0 && d[c] != dir[c]) return false;
    out[c] = dir[c] != 0 ? dir[c] : d[c];
  }
  return true;
}

bool PivotTurnSearch::Run::tryFinish() {
  const SupportStep& s = node_.step;
  if (s.set.pivot() < 0) return false;
  double psi = 0.0, theta = 0.0, l = 0.0;
  if (!geometry_.pivotOnto(s.anchor, goal_, s.pose.psi, psi, theta, l)) return false;
  // Within a step ahead of the pivot's way (half a step when it has none yet), and half a
  // stroke step.
  auto way = [](double d) { return std::abs(d) < 1e-12 ? 0 : (d > 0.0 ? 1 : -1); };
  const double ahead = node_.dir[0] * (psi - s.pose.psi);
  const bool near = node_.dir[0] != 0 ? ahead >= -1e-9 && ahead <= a_ + 1e-9
                                      : std::abs(psi - s.pose.psi) <= 0.5 * a_ + 1e-9;
  if (!near || std::abs(s.anchor.stroke - l) > 0.5 * ds_ + 1e-9) return false;
  std::array<int, 3> dir{};
  if (!keepsWay(node_.dir, {way(psi - s.pose.psi), way(psi - s.pose.psi), 0}, dir)) return false;
  const std::vector<SupportStep> tail = owner_.finish(s, psi, theta, l);
  if (tail.empty()) return false;
  // Nor does a slider turn back where the last bit begins.
  if (!s.rest && tail.front().set == s.set &&
      reverses(node_.slip, geometry_.slipDirections(s.q, tail.front().q), s.set))
    return false;
  keepPath(tail);
  return true;
}

void PivotTurnSearch::Run::keepPath(const std::vector<SupportStep>& tail) {
  std::vector<SupportStep> path;
  for (int n = id_; n >= 0; n = nodes_[n].parent) path.push_back(nodes_[n].step);
  std::reverse(path.begin(), path.end());
  path.insert(path.end(), tail.begin(), tail.end());
  const int pivots = pivotRuns(path), runs = phaseRuns(path);
  const double length = pathLength(path, ls_);
  if (!result_.found)
    stop_at_ = std::min(
        settings_.max_expansions,
        result_.expansions + static_cast<long>(std::ceil(ss_.search_on * result_.expansions)));
  const bool better = !result_.found || pivots < best_pivots_ ||
                      (pivots == best_pivots_ &&
                       (runs < best_runs_ || (runs == best_runs_ && length < best_length_)));
  if (!better) return;
  result_.found = true;
  result_.steps = std::move(path);
  best_pivots_ = pivots;
  best_runs_ = runs;
  best_length_ = length;
}

void PivotTurnSearch::Run::pivotMoves(Node& next) {
  const SupportStep& s = node_.step;
  next.pivots = node_.pivots;
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj)
      for (int dl = -1; dl <= 1; ++dl) {
        if (di == 0 && dj == 0 && dl == 0) continue;
        const int world = di + dj > 0 ? 1 : di + dj < 0 ? -1 : 0;
        if (!keepsWay(node_.dir, {di, world, 0}, next.dir)) continue;
        PivotAnchor moved = s.anchor;
        moved.stroke += dl * ds_;
        const JigPose pose =
            geometry_.pivotPose(moved, s.pose.psi + di * a_, s.pose.theta + dj * a_);
        if (!search_.stepTo(s, pose, s.set, moved, next.step)) continue;
        // A slider whose slip turns back sticks on the way: that is a rest, not a move.
        next.slip = geometry_.slipDirections(s.q, next.step.q);
        if (!s.rest && reverses(node_.slip, next.slip, s.set)) continue;
        if (!slidersKeepSliding(next.slip, s.set)) continue;
        next.g = node_.g + moveCost(s, next.step, ss_);
        push(next);
      }
}

void PivotTurnSearch::Run::rigidMoves(Node& next) {
  const SupportStep& s = node_.step;
  next.pivots = node_.pivots;
  next.slip = VecC();
  for (int dj : {1, -1}) {
    if (!keepsWay(node_.dir, {0, dj, 0}, next.dir)) continue;  // the world angle turns with theta
    JigPose pose = s.pose;
    pose.theta += dj * a_;
    if (!search_.stepTo(s, pose, s.set, PivotAnchor{}, next.step)) continue;
    next.g = node_.g + moveCost(s, next.step, ss_);
    push(next);
  }
}

void PivotTurnSearch::Run::switches(Node& next, int depth) {
  const SupportStep& s = node_.step;
  next.slip = VecC();
  next.dir = {};
  for (const ContactSet& set : restSets(s.pose, s.set.touching)) {
    if (set == s.set) continue;
    next.pivots = node_.pivots + (set.pivot() >= 0 ? 1 : 0);
    if (next.pivots > depth) continue;
    PivotAnchor anchor;
    if (!search_.anchorFor(s.pose, set, anchor)) continue;
    if (!search_.stepTo(s, s.pose, set, anchor, next.step)) continue;
    // The fingers that move at rest take their time.
    next.g = node_.g + ss_.switch_cost + (set.pivot() >= 0 ? settings_.pivot_cost : 0.0) +
             strokeTravel(s.q, next.step.q);
    push(next);
  }
}

SupportPath PivotTurnSearch::search(const Pose& start, double start_theta, const Pose& goal,
                                    const std::atomic<bool>* cancel) {
  return Run(*this, start, start_theta, goal, cancel).run();
}

}  // namespace rbsf::planner
