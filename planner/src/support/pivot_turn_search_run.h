#pragma once
/// \file
/// \brief One PivotTurnSearch::search() as an object (private to the planner module): the
///        leads (rigid runs from the start), the lattice of the pivot finger at hand with its
///        open list, and the best path so far are its members, and the search's steps (roots,
///        leads, seeds, budget, expansion, the join to the goal) its member functions. The
///        order of expansions and of every floating-point operation is the search's
///        (pivot_turn_search.h): the same inputs give the same path.

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

  /// \brief Searches every pivot finger in turn until the budget is spent or the search is
  ///        done, and returns the best simple turn found (or why none was).
  SupportPath run();

 private:
  using Clock = std::chrono::steady_clock;
  /// \brief An open-list entry: g + heuristic_weight * heuristic, and the node's index.
  using Entry = std::pair<double, int>;
  /// \brief Where a pivot may start: the start itself (empty), or the end of a rigid run
  ///        from it, with the run's cost.
  struct Lead {
    std::vector<SupportStep> steps;
    double g = 0.0;
  };
  /// \brief A lattice node of the pivot at hand: its support state, cost, parent, lead and
  ///        (psi, theta, stroke) indices.
  struct Node {
    SupportStep step;
    double g = 0.0;
    int parent = -1;
    int lead = 0;
    int i = 0, j = 0, l = 0;
    VecC slip;  ///< of the move that reached the node (empty at rest)
  };
  /// \brief What the budget check says of the expansion at hand.
  enum class Budget {
    kGoOn,    ///< expand the node
    kStop,    ///< stop this pivot finger (and, with a flag set, the search)
    kCancel,  ///< stop now with result_.message "stopped"
  };

  // Leads and the pivot at hand (pivot_turn_search_run.cpp).
  /// \brief The part at rest on the start pose with `set` in `s`; false when not valid.
  bool root(const ContactSet& set, SupportStep& s);
  /// \brief The leads: the start, then for every set of two or more touching fingers all
  ///        sticking, its rest and the rigid runs from it either way.
  void collectLeads();
  /// \brief The leads of the rigid run from `r` in direction `dir`, one per angle_step.
  void rigidLeads(const SupportStep& r, int dir);
  /// \brief Prepares the pivot about finger k: its anchor, where it must end and its
  ///        touching fingers, and an empty lattice; false when finger k cannot pivot the part
  ///        onto the goal.
  bool startPivot(int k);
  /// \brief Roots of the pivot at hand: each lead with each of its touching fingers.
  void seedPivot();
  /// \brief The pivot's heuristic of `s`: part angle, stroke and base angle to its end.
  double heuristic(const SupportStep& s) const;
  /// \brief Adds `node` unless its lattice node and fingers hold one as cheap, and opens it.
  void push(const Node& node);

  // The main loop and one expansion (pivot_turn_search_run.cpp).
  /// \brief Expands the pivot at hand until its lattice is searched out, a path is found or
  ///        the budget stops it; false when the search was cancelled.
  bool explorePivot();
  /// \brief Pops the best open node as the expansion at hand; false when a cheaper node of
  ///        its lattice node has replaced it.
  bool take();
  /// \brief Counts the expansion against the budget (expansions, cancel, time).
  Budget spend();
  /// \brief Joins the node at hand to the goal when it is within half a step of the pivot's
  ///        end and the finish is valid, keeping the path; true when it was joined.
  bool tryFinish();
  /// \brief The path through the node at hand (its lead, the lattice chain, then `tail`);
  ///        the first sets how long the search goes on (search_on); the one with the fewest
  ///        phase runs, then the shortest, is kept.
  void keepPath(const std::vector<SupportStep>& tail);
  /// \brief The 26 lattice moves from the node at hand, each built in `next`.
  void latticeMoves(Node& next);
  /// \brief The switches of touching fingers at rest at the node at hand, built in `next`.
  void switches(Node& next);

  PivotTurnSearch& owner_;
  SupportSearch& search_;
  const PivotTurnSettings& settings_;
  const Clock::time_point started_;
  SupportGeometry& geometry_;
  const SupportSearchSettings& ss_;
  const Pose goal_;
  const std::atomic<bool>* cancel_;
  const double start_theta_;
  const double a_;           ///< settings_.angle_step
  const double ds_;          ///< settings_.stroke_step
  const double ls_;          ///< ss_.length_scale
  const int m_;              ///< fingers
  const std::uint32_t all_;  ///< every finger
  const JigPose p0_;         ///< the start
  const ContactSet placed_;  ///< the placement rule's fingers at the start
  std::vector<Lead> leads_;
  SupportPath result_;

  int best_runs_ = 0;
  double best_length_ = 0.0;
  bool budget_out_ = false;
  bool timed_out_ = false;
  long stop_at_;  ///< after the first path: search_on times its cost

  // The pivot at hand (startPivot).
  int k_ = -1;                                               ///< its finger
  PivotAnchor anchor_;                                       ///< its anchor at the start
  double psi_goal_ = 0.0, theta_goal_ = 0.0, l_goal_ = 0.0;  ///< where it must end
  std::vector<std::uint32_t> touchings_;                     ///< k and at least one slider
  std::vector<Node> nodes_;
  std::unordered_map<std::uint64_t, double> best_;  ///< lowest g per lattice node and fingers
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open_;

  // The expansion at hand.
  int id_ = -1;  ///< its node
  Node node_;    ///< a copy: pushes may move the lattice's nodes
};

}  // namespace rbsf::planner
