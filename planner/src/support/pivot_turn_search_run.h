#pragma once
/// \file
/// \brief One PivotTurnSearch::search() as an object (private to the planner module): the
///        lattice with its open list and the best path so far are its members, and the
///        search's steps (roots, one depth of pivots, budget, expansion, the join to the goal)
///        its member functions. The order of expansions and of every floating-point
///        operation is the search's (pivot_turn_search.h): the same inputs give the same path.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rbsf/planner/support/pivot_turn_search.h"

namespace rbsf::planner {

/// \brief The simple-turn search of pivot_turn_search.h from one start to one goal; run()
///        once per object.
class PivotTurnSearch::Run {
 public:
  /// \brief Prepares the search of `owner` from the part at rest at `start` with base angle
  ///        `start_theta` to `goal`. `cancel`, when set and true, stops the search.
  Run(PivotTurnSearch& owner, const Pose& start, double start_theta, const Pose& goal,
      const std::atomic<bool>* cancel);

  /// \brief Searches with at most 1, 2, ... max_pivots pivots until a depth finds a turn, the
  ///        budget is spent or the search is cancelled, and returns the best simple turn
  ///        found (or why none was).
  SupportPath run();

 private:
  using Clock = std::chrono::steady_clock;
  /// \brief An open-list entry: g + heuristic_weight * heuristic, and the node's index.
  using Entry = std::pair<double, int>;
  /// \brief A lattice node: its support state, cost, parent, pivots so far, the slip of the
  ///        move that reached it (empty at rest) and the way its run turns the part on the
  ///        base (psi) and in the world (psi + theta), 0 until a move turns it: a run never
  ///        turns back in either (the third entry is unused).
  struct Node {
    SupportStep step;
    double g = 0.0;
    int parent = -1;
    int pivots = 0;
    VecC slip;
    std::array<int, 3> dir{};
  };
  /// \brief Whether a move turning the part by `d` (Node::dir's entries) keeps the way `dir`
  ///        goes, into `out`.
  static bool keepsWay(const std::array<int, 3>& dir, const std::array<int, 3>& d,
                       std::array<int, 3>& out);
  /// \brief A lattice cell: (psi, theta, X, Y) indices, touching, sticking and pivots.
  using CellKey = std::array<std::int32_t, 7>;
  /// \brief FNV-1a over a CellKey.
  struct CellKeyHash {
    std::size_t operator()(const CellKey& k) const;
  };
  /// \brief What the budget check says of the expansion at hand.
  enum class Budget {
    kGoOn,    ///< expand the node
    kStop,    ///< stop the search
    kCancel,  ///< stop now with result_.message "stopped"
  };

  /// \brief restSetsWithin() the `touching` fingers and those the placement rule reaches at
  ///        `pose`, with at most max_sliders sliding.
  std::vector<ContactSet> restSets(const JigPose& pose, std::uint32_t touching) const;
  /// \brief Roots: the start at rest on every valid set (restSets).
  void seed();
  /// \brief Expands the lattice with at most `depth` pivots until it is searched out or the
  ///        budget stops it; false when the search was cancelled.
  bool explore(int depth);
  /// \brief The lattice cell of `node`.
  CellKey key(const Node& node) const;
  /// \brief The heuristic of `s`: its world pose's distance to the goal.
  double heuristic(const SupportStep& s) const;
  /// \brief The cost of the fingers' moves at rest from a to b: their strokes' travel over
  ///        the length scale.
  double strokeTravel(const VecQ& a, const VecQ& b) const;
  /// \brief Adds `node` unless its lattice cell holds one as cheap, and opens it.
  void push(const Node& node);
  /// \brief Pops the best open node as the expansion at hand; false when a cheaper node of
  ///        its cell has replaced it.
  bool take();
  /// \brief Counts the expansion against the budget (expansions, cancel, time).
  Budget spend();
  /// \brief Joins the pivot node at hand to the goal when it is within half a step of the
  ///        end its anchor gives and the finish is valid, keeping the path; true when joined.
  bool tryFinish();
  /// \brief The path through the node at hand, then `tail`; the first sets how long the
  ///        search goes on (search_on); the one with the fewest phase runs, then the
  ///        shortest, is kept.
  void keepPath(const std::vector<SupportStep>& tail);
  /// \brief The 26 lattice moves of the pivot at hand, each built in `next`.
  void pivotMoves(Node& next);
  /// \brief The base's steps of the rigid run at hand, each built in `next`.
  void rigidMoves(Node& next);
  /// \brief The switches of contact set at rest at the node at hand, built in `next`.
  void switches(Node& next, int depth);

  PivotTurnSearch& owner_;
  SupportSearch& search_;
  const PivotTurnSettings& settings_;
  const Clock::time_point started_;
  SupportGeometry& geometry_;
  const SupportSearchSettings& ss_;
  const Pose goal_;
  const std::atomic<bool>* cancel_;
  const double start_theta_;
  const double a_;    ///< settings_.angle_step
  const double ds_;   ///< settings_.stroke_step
  const double ls_;   ///< ss_.length_scale
  const int m_;       ///< fingers
  const JigPose p0_;  ///< the start
  SupportPath result_;

  int best_pivots_ = 0;
  int best_runs_ = 0;
  double best_length_ = 0.0;
  bool budget_out_ = false;
  bool timed_out_ = false;
  long stop_at_;  ///< after the first path: search_on times its cost

  std::vector<Node> nodes_;
  std::unordered_map<CellKey, double, CellKeyHash> best_;  ///< lowest g per lattice cell
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open_;

  // The expansion at hand.
  int id_ = -1;  ///< its node
  Node node_;    ///< a copy: pushes may move the lattice's nodes
};

}  // namespace rbsf::planner
