// SupportSearch::Run: the setup, the main loop and one expansion (moves and switches) of the
// search of support_search.h; the joins of the trees are in support_search_join.cpp.
#include <algorithm>
#include <cmath>
#include <string>

#include "support_search_run.h"

namespace rbsf::planner {

SupportSearch::Run::Run(SupportSearch& search, const Pose& start, double start_theta,
                        const Pose& goal, const std::atomic<bool>* cancel)
    : search_(search),
      geometry_(search.geometry_),
      settings_(search.settings_),
      started_(Clock::now()),
      goal_(goal),
      cancel_(cancel),
      a_(search.settings_.angle_step),
      d_(search.settings_.xy_step),
      ls_(search.settings_.length_scale),
      m_(search.model_.numFingers()),
      start_pose_(JigPose::fromWorld(start, start_theta)) {
  collectGoals();
  initReach(start);
}

SupportPath SupportSearch::Run::run() {
  explore();
  return std::move(result_);
}

void SupportSearch::Run::collectGoals() {
  const Cell& cell = search_.model_.cell();
  const double t_lo = cell.base.theta_min + settings_.support.theta_margin;
  const double t_hi = cell.base.theta_max - settings_.support.theta_margin;
  for (double th = t_lo; th <= t_hi + 1e-12; th += settings_.goal_theta_step)
    for (int turn = -1; turn <= 1; ++turn) {
      JigPose g = JigPose::fromWorld(goal_, th);
      g.psi += 2.0 * M_PI * turn;
      if (std::abs(g.psi) <= 2.0 * M_PI + 1e-9) goals_.push_back(g);
    }
}

void SupportSearch::Run::initReach(const Pose& start) {
  SupportReach& reach = result_.reach;
  reach.measured = true;
  reach.psi_min = reach.psi_max = start_pose_.psi;
  reach.phi_min = reach.phi_max = start.phi;
  reach.closest = start;
  reach.closest_score = INFINITY;
}

double SupportSearch::Run::poseHeuristic(const JigPose& p) const {
  double h = INFINITY;
  for (const JigPose& g : goals_) h = std::min(h, poseDistance(p, g, ls_));
  return h;
}

bool SupportSearch::Run::pivotTarget(const SupportStep& s, double& psi, double& th, double& l) {
  return geometry_.pivotOnto(s.anchor, goal_, s.pose.psi, psi, th, l);
}

double SupportSearch::Run::heuristic(const SupportStep& s, double h) {
  if (s.set.pivot() < 0) return h;
  double psi, th, l;
  if (!pivotTarget(s, psi, th, l)) return h + 2.0 * settings_.switch_cost;
  return std::min(h, std::abs(psi - s.pose.psi) + std::abs(th - s.pose.theta) +
                         std::abs(l - s.anchor.stroke) / ls_);
}

SupportSearch::CellKey SupportSearch::Run::pivotKey(const SupportStep& s, int dpsi, int dtheta,
                                                    int finger) const {
  return CellKey{static_cast<std::int32_t>(std::lround(s.pose.psi / a_)) + dpsi,
                 static_cast<std::int32_t>(std::lround(s.pose.theta / a_)) + dtheta,
                 finger,
                 0,
                 static_cast<std::int32_t>(s.set.touching),
                 0};
}

SupportSearch::CellKey SupportSearch::Run::meetKey(const SupportStep& s) const {
  return CellKey{static_cast<std::int32_t>(std::lround(s.pose.psi / a_)),
                 0,
                 0,
                 0,
                 static_cast<std::int32_t>(s.set.touching),
                 0};
}

void SupportSearch::Run::noteReached(const SupportStep& s, double score) {
  SupportReach& reach = result_.reach;
  const Pose w = s.pose.world();
  reach.psi_min = std::min(reach.psi_min, s.pose.psi);
  reach.psi_max = std::max(reach.psi_max, s.pose.psi);
  reach.phi_min = std::min(reach.phi_min, w.phi);
  reach.phi_max = std::max(reach.phi_max, w.phi);
  ++reach.poses;
  if (score < reach.closest_score) {
    reach.closest_score = score;
    reach.closest = w;
    reach.closest_position = std::hypot(goal_.x - w.x, goal_.y - w.y);
    reach.closest_angle = std::remainder(goal_.phi - w.phi, 2.0 * M_PI);
  }
}

void SupportSearch::Run::push(int t, const SupportStep& s, double g, int parent) {
  Tree& tree = trees_[t];
  const CellKey k = search_.key(s.pose, s.set);
  if (search_.blocked_.count(k) != 0) return;
  const auto it = tree.best.find(k);
  if (it != tree.best.end() && it->second <= g + 1e-12) return;
  tree.best[k] = g;
  double h = poseDistance(s.pose, start_pose_, ls_);  // the goal tree grows towards the start
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
}

void SupportSearch::Run::seed(int t, const JigPose& pose) {
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
    if (search_.restAt(pose, set, s)) push(t, s, 0.0, -1);
  }
}

void SupportSearch::Run::explore() {
  // Roots: every valid set of the placement rule's fingers at the start, and at the goal seen
  // from each candidate base angle.
  seed(0, start_pose_);
  if (trees_[0].nodes.empty()) {
    result_.message = "the start support is not in balance with the required margins";
    return;
  }
  for (const JigPose& g : goals_) seed(1, g);

  int turn = 1;
  while (!trees_[0].open.empty() || !trees_[1].open.empty()) {
    turn = trees_[1 - turn].open.empty() ? turn : 1 - turn;
    if (!take(turn)) continue;
    const Budget budget = spend();
    if (budget == Budget::kStop) break;
    if (budget == Budget::kGiveUp) return;
    expand();
  }
  if (!result_.found && result_.message.empty())
    result_.message =
        result_.expansions > settings_.max_expansions
            ? "no support path within " + std::to_string(settings_.max_expansions) + " expansions"
            : "both trees were searched out without meeting (at this resolution and these margins)";
}

bool SupportSearch::Run::take(int t) {
  Tree& tree = trees_[t];
  t_ = t;
  id_ = tree.open.top().second;
  tree.open.pop();
  node_ = tree.nodes[id_];
  return !(tree.best[search_.key(node_.step.pose, node_.step.set)] < node_.g - 1e-12);
}

SupportSearch::Run::Budget SupportSearch::Run::spend() {
  if (result_.found && result_.expansions >= stop_at_) return Budget::kStop;
  if (++result_.expansions > settings_.max_expansions) return Budget::kStop;
  if ((result_.expansions & 255) == 0) {
    if (cancel_ != nullptr && cancel_->load()) {
      result_.message = "stopped";
      return Budget::kGiveUp;
    }
    if (std::chrono::duration<double>(Clock::now() - started_).count() > settings_.time_limit) {
      if (result_.found) return Budget::kStop;
      result_.message = "no support path within the time limit";
      return Budget::kGiveUp;
    }
  }
  return Budget::kGoOn;
}

void SupportSearch::Run::expand() {
  const SupportStep& s = node_.step;
  if (t_ == 0 && node_.h <= settings_.goal_connect) connectGoal();
  // In the goal tree a switch away from s starts (in time) the run from s towards the
  // node s came from: its sliders must break away there.
  can_leave_ = true;
  if (t_ == 1 && node_.parent >= 0 && settings_.support.require_breakaway) {
    const SupportStep& towards = trees_[t_].nodes[node_.parent].step;
    if (towards.set == s.set)
      can_leave_ = geometry_.breaksAway(s.q, s.set, geometry_.slipDirections(s.q, towards.q));
  }
  switch (s.set.phase()) {
    case Phase::kU:
      slideMoves();
      break;
    case Phase::kP:
      pivotMoves();
      break;
    default:
      rigidMoves();
      break;
  }
  switches();
}

void SupportSearch::Run::slideMoves() {
  static const int kMoves[][4] = {{1, 0, 0, 0}, {-1, 0, 0, 0}, {0, 1, 0, 0},  {0, -1, 0, 0},
                                  {0, 0, 1, 0}, {0, 0, -1, 0}, {0, 0, 0, 1},  {0, 0, 0, -1},
                                  {0, 0, 1, 1}, {0, 0, 1, -1}, {0, 0, -1, 1}, {0, 0, -1, -1},
                                  {1, 0, 1, 0}, {1, 0, -1, 0}, {-1, 0, 1, 0}, {-1, 0, -1, 0}};
  const SupportStep& s = node_.step;
  for (const auto& mv : kMoves)
    tryMove(JigPose{s.pose.X + mv[0] * d_, s.pose.Y + mv[1] * d_, s.pose.psi + mv[2] * a_,
                    s.pose.theta + mv[3] * a_},
            s.set, s.anchor);
}

void SupportSearch::Run::pivotMoves() {
  static const int kMoves[][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},   {0, -1, 0}, {1, 1, 0},
                                  {1, -1, 0}, {-1, 1, 0}, {-1, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  const SupportStep& s = node_.step;
  for (const auto& mv : kMoves) {
    PivotAnchor anchor = s.anchor;
    anchor.stroke += mv[2] * d_;
    tryMove(geometry_.pivotPose(anchor, s.pose.psi + mv[0] * a_, s.pose.theta + mv[1] * a_), s.set,
            anchor);
  }
}

void SupportSearch::Run::rigidMoves() {
  static const int kMoves[][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  const SupportStep& s = node_.step;
  for (const auto& mv : kMoves)
    tryMove(JigPose{s.pose.X, s.pose.Y + mv[1] * d_, s.pose.psi, s.pose.theta + mv[0] * a_}, s.set,
            s.anchor);
}

void SupportSearch::Run::switches() {
  // Every contact slides, one sticks, all stick; a finger touches (sliding, or sticking
  // beside a sticking one) or lets go (a sliding one, or a sticking one beside another).
  const SupportStep& s = node_.step;
  const std::uint32_t touching = s.set.touching;
  if (s.set.sticking != 0) trySwitch(ContactSet{touching, 0u});
  for (int k = 0; k < m_; ++k)
    if ((touching >> k) & 1u && s.set.sticking != (1u << k))
      trySwitch(ContactSet{touching, 1u << k});
  if (s.set.sticking != touching) trySwitch(ContactSet{touching, touching});
  for (int j = 0; j < m_; ++j) {
    const std::uint32_t bit = 1u << j;
    if (!s.set.sticks(j)) trySwitch(ContactSet{touching ^ bit, s.set.sticking});
    if (s.set.sticks(j) && s.set.stickingCount() > 1)
      trySwitch(ContactSet{touching & ~bit, s.set.sticking & ~bit});  // a sticking one lets go
    if (!s.set.touches(j) && s.set.sticking != 0)
      trySwitch(ContactSet{touching | bit, s.set.sticking | bit});  // placed to stick
  }
}

void SupportSearch::Run::tryMove(const JigPose& pose, const ContactSet& set,
                                 const PivotAnchor& anchor) {
  const SupportStep& s = node_.step;
  SupportStep mid;
  if (!search_.stepTo(s, lerpPose(s.pose, pose, 0.5), set, anchor, mid, t_ == 1) ||
      !search_.stepTo(mid, pose, set, anchor, next_, t_ == 1)) {
    refused(pose);
    return;
  }
  add(node_.g + moveCost(s, next_, settings_));
}

void SupportSearch::Run::trySwitch(const ContactSet& set) {
  const SupportStep& s = node_.step;
  PivotAnchor anchor;
  if (!can_leave_ || !search_.anchorFor(s.pose, set, anchor)) return;
  if (set.pivot() >= 0 && set.pivot() == s.set.pivot()) anchor = s.anchor;
  if (search_.stepTo(s, s.pose, set, anchor, next_)) add(node_.g + settings_.switch_cost);
}

void SupportSearch::Run::refused(const JigPose& pose) {
  SupportReach& reach = result_.reach;
  if (t_ == 0 && poseHeuristic(pose) < reach.closest_score)
    ++reach.refused[static_cast<int>(search_.refusal_)];
}

void SupportSearch::Run::add(double g) {
  Tree& tree = trees_[t_];
  const std::size_t before = tree.nodes.size();
  push(t_, next_, g, id_);
  if (tree.nodes.size() <= before) return;
  const int added = static_cast<int>(tree.nodes.size()) - 1;
  if (next_.set.phase() == Phase::kU)
    meet(t_, added);
  else if (next_.set.phase() == Phase::kP)
    meetPivot(t_, added);
}

SupportPath SupportSearch::search(const Pose& start, double start_theta, const Pose& goal,
                                  const std::atomic<bool>* cancel) {
  return Run(*this, start, start_theta, goal, cancel).run();
}

}  // namespace rbsf::planner
