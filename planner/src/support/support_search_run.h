#pragma once
/// \file
/// \brief One SupportSearch::search() as an object (private to the planner module): the two
///        trees with their open lists, the goal candidates, the start tree's reach and the
///        best path so far are its members, and the search's steps (roots, expansion, moves,
///        switches, the joins of the trees) its member functions. The order of expansions and
///        of every floating-point operation is the search's (support_search.h): the same
///        inputs give the same path.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rbsf/planner/support/support_search.h"

namespace rbsf::planner {

/// \brief A node of a search tree: a support state, its cost from the tree's roots, the node
///        it was reached from and the tree's heuristic there.
struct SupportSearch::Node {
  SupportStep step;
  double g = 0.0;
  int parent = -1;
  double h = 0.0;  ///< the tree's heuristic at the node (start tree: to the goal)
};

/// \brief The bidirectional search of support_search.h from one start to one goal; run()
///        once per object.
class SupportSearch::Run {
 public:
  /// \brief Prepares the search of `search` from the part at rest at `start` with base angle
  ///        `start_theta` to `goal`: the goal candidates and the start tree's reach.
  ///        `cancel`, when set and true, stops the search.
  Run(SupportSearch& search, const Pose& start, double start_theta, const Pose& goal,
      const std::atomic<bool>* cancel);

  /// \brief Grows both trees until the budget is spent or the search is done, and returns
  ///        the best path found (or why none was).
  SupportPath run();

 private:
  using Clock = std::chrono::steady_clock;
  /// \brief An open-list entry: g + heuristic_weight * h, and the node's index.
  using Entry = std::pair<double, int>;
  /// \brief One tree: from the start (forward) or from the goal's supports (backward; its
  ///        chains read from a node to its root run to the goal).
  struct Tree {
    std::vector<Node> nodes;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    std::unordered_map<CellKey, double, CellKeyHash> best;               ///< lowest g per cell
    std::unordered_map<CellKey, std::vector<int>, CellKeyHash> sliding;  ///< U nodes by cell
    std::unordered_map<CellKey, std::vector<int>, CellKeyHash> pivots;   ///< P nodes by cell
  };
  /// \brief What the budget check says of the expansion at hand.
  enum class Budget {
    kGoOn,    ///< expand the node
    kStop,    ///< stop and keep what was found
    kGiveUp,  ///< stop now with result_.message (cancelled, or no path in the time limit)
  };

  // Setup (support_search_run.cpp).
  /// \brief The goal pose seen from base angles across the range, psi +- 2 pi.
  void collectGoals();
  /// \brief The start tree's reach before any node: the start's angles, nothing closest.
  void initReach(const Pose& start);
  /// \brief Roots of tree `t` at `pose`: every valid set of the placement rule's fingers.
  void seed(int t, const JigPose& pose);
  /// \brief Adds the node `s` with cost `g` to tree `t` unless its cell is blocked or holds
  ///        a node as cheap; opens it and files it for the joins.
  void push(int t, const SupportStep& s, double g, int parent);
  /// \brief The start tree's reach widened by `s`, whose distance to the goal is `score`.
  void noteReached(const SupportStep& s, double score);
  /// \brief The distance from `p` to the nearest goal candidate.
  double poseHeuristic(const JigPose& p) const;
  /// \brief The start tree's heuristic of `s`, whose poseHeuristic is `h`: for a pivot, also
  ///        the pivot that puts the part on the goal.
  double heuristic(const SupportStep& s, double h);
  /// \brief The pivot that puts the part on the goal (SupportGeometry::pivotOnto).
  bool pivotTarget(const SupportStep& s, double& psi, double& th, double& l);
  /// \brief The cell in which pivots meet: part and base angle (shifted by `dpsi`, `dtheta`
  ///        steps), touching fingers and pivot finger.
  CellKey pivotKey(const SupportStep& s, int dpsi, int dtheta, int finger) const;
  /// \brief The cell in which sliding nodes meet: part angle and touching fingers.
  CellKey meetKey(const SupportStep& s) const;

  // The main loop and one expansion (support_search_run.cpp).
  /// \brief Both trees grown in turns; leaves the outcome in result_.
  void explore();
  /// \brief Pops tree `t`'s best open node as the expansion at hand; false when a cheaper
  ///        node of its cell has replaced it.
  bool take(int t);
  /// \brief Counts the expansion against the budget (expansions, cancel, time).
  Budget spend();
  /// \brief Expands the node at hand: the join to the goal, the moves, the switches.
  void expand();
  /// \brief Slides of the node at hand: X, Y, psi, theta, psi with theta or with X.
  void slideMoves();
  /// \brief Pivots of the node at hand: psi, theta or both, or the pivot's stroke.
  void pivotMoves();
  /// \brief Rigid moves of the node at hand: the base turns or every finger strokes alike.
  void rigidMoves();
  /// \brief Switches at the pose at hand: every contact slides, one sticks, all stick; a
  ///        finger touches or lets go.
  void switches();
  /// \brief The move from the node at hand to `pose` with `set` and `anchor`, checked at its
  ///        midpoint and end; added, or counted as refused.
  void tryMove(const JigPose& pose, const ContactSet& set, const PivotAnchor& anchor);
  /// \brief The switch from the node at hand to `set` at its pose, added when valid.
  void trySwitch(const ContactSet& set);
  /// \brief A refused start-tree move that would have gone beyond the closest pose counts
  ///        against the rule it broke (the reachability answer).
  void refused(const JigPose& pose);
  /// \brief Adds next_ with cost `g` as a child of the node at hand and tries the joins
  ///        from it.
  void add(double g);

  // Paths and the joins of the trees (support_search_join.cpp).
  /// \brief The straight slide or the pivot from the start-tree node at hand to the goal.
  void connectGoal();
  /// \brief A path: the forward chain to `f`, `middle`, then the backward chain from `b` (if
  ///        any). The first sets how long the search goes on (search_on); the one with the
  ///        fewest phase runs, then the shortest, is kept.
  void finish(int f, const std::vector<SupportStep>& middle, int b);
  /// \brief A new sliding node `id` of tree `t` meets the other tree's sliding nodes in its
  ///        cell by a straight slide.
  bool meet(int t, int id);
  /// \brief A new pivot node `id` of tree `t` meets the other tree's pivots on another
  ///        finger nearby by a bridge (bridgePivots).
  bool meetPivot(int t, int id);
  /// \brief Two pivots on fingers k (`from`) and j (`to`) with the same touching fingers:
  ///        pivot about k to the part angle of the hand-over, switch the stick from k to j
  ///        there and pivot about j onto `to`; empty when one of them is not valid.
  std::vector<SupportStep> bridgePivots(const SupportStep& from, const SupportStep& to);
  /// \brief The part angle, along the pivot about `from`'s anchor, at which finger j's line
  ///        enters the part at `to`'s anchor; NaN when there is none near both.
  double handOverAngle(const SupportStep& from, const SupportStep& to);
  /// \brief Bisection of entryOffset's sign change between `lo` (its value `f_lo`) and `hi`.
  double bisectHandOver(const SupportStep& from, const SupportStep& to, double lo, double hi,
                        double f_lo);
  /// \brief How far (wrapped boundary parameter) finger j's entry into the part is from
  ///        `to`'s anchor with `from`'s pivot at part angle `psi`; false when it misses.
  bool entryOffset(const SupportStep& from, const SupportStep& to, double psi, double& value);

  SupportSearch& search_;
  SupportGeometry& geometry_;
  const SupportSearchSettings& settings_;
  const Clock::time_point started_;
  const Pose goal_;
  const std::atomic<bool>* cancel_;
  const double a_;   ///< settings_.angle_step
  const double d_;   ///< settings_.xy_step
  const double ls_;  ///< settings_.length_scale
  const int m_;      ///< fingers
  const JigPose start_pose_;
  std::vector<JigPose> goals_;  ///< goal candidates (collectGoals)
  Tree trees_[2];               ///< 0: from the start, 1: from the goal
  SupportPath result_;

  long stop_at_ = 0;  ///< the expansions after which the search stops once a path is found
  int best_runs_ = 0;
  double best_length_ = 0.0;
  std::vector<SupportStep> candidate_;  ///< finish()'s path, kept to reuse its storage

  // The expansion at hand.
  int t_ = 0;                                  ///< its tree
  int id_ = -1;                                ///< its node
  Node node_;                                  ///< a copy: pushes may move the tree's nodes
  bool can_leave_ = true;                      ///< a switch away from it may start a run
  SupportStep next_;                           ///< the move's or switch's end (tryMove, trySwitch)
  std::vector<std::pair<double, int>> order_;  ///< goal candidates by distance (connectGoal)
};

}  // namespace rbsf::planner
