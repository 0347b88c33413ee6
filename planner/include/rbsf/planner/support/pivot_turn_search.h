#pragma once
/// \file
/// \brief Simple turns: the part turned by one pivot, the way a cell engineer would turn it
///        by hand, found before the general support search (support_search.h) is tried.
///
/// A simple turn has three kinds of run, each from rest to rest:
///   1. optionally, a **rigid** run at the start: every touching tip sticks and the base
///      turns (fingers may let go or touch first, at rest);
///   2. a **pivot** about finger k: its tip keeps its point xi_k of the part at stroke l_k,
///      the other touching tips slide, and the part angle psi, the base angle theta and the
///      stroke l_k all change along the run. The touching fingers may change at a rest on
///      the way (the pivot goes on about the same point);
///   3. optionally, a **rigid** run at the end that turns the base onto the goal.
/// The pivot's anchor fixes where it must end: the tip's world point on the goal pose fixes
/// the stroke and the base angle (SupportGeometry::pivotOnto), so the pivot ends at that part
/// angle and stroke, at any base angle from which a rigid run reaches the goal's.
///
/// Search: for each pivot finger touching at the start, weighted A* over a lattice of
/// (psi, theta, l_k, touching fingers) with steps `angle_step` and `stroke_step`, seeded
/// with the start and every base angle the start's rigid runs reach. Moves are the 26
/// lattice neighbours and the switches of touching fingers at rest, each taken when its end
/// support is valid with the move's slip and, from rest, breaks away
/// (SupportSearch::stepTo). Cost and heuristic are the support search's (metres over
/// `length_scale`, radians as they are, weighted by the margin; `switch_cost` a switch). A
/// node within half a step of the pivot's end is joined to it by a straight pivot and then
/// to the goal by a rigid run. Of the paths found (one per pivot finger) the one with the
/// fewest phase runs, then the shortest, is kept.
///
/// Cells blocked in the SupportSearch are not entered here either. Deterministic: the same
/// inputs give the same path, and a budget in expansions gives it on any machine where the
/// time limit does not bind first. Analysis-time code (allocates).

#include <atomic>
#include <vector>

#include "rbsf/planner/support/support_search.h"

namespace rbsf::planner {

/// \brief Settings of PivotTurnSearch (file comment).
struct PivotTurnSettings {
  double angle_step = 3.75 * M_PI / 180;  ///< psi and theta lattice [rad]
  double stroke_step = 0.015;             ///< the pivot's stroke lattice [m]
  double heuristic_weight = 2.0;          ///< weighted A* (>= 1)
  long max_expansions = 60000;            ///< lattice nodes expanded, every finger together
  double time_limit = 30.0;  ///< wall time [s] (infinity: none); the budget above is the machine's
};

/// \brief The search of the file comment; one per thread. Uses `search`'s geometry, steps,
///        blocked cells and cost settings.
class PivotTurnSearch {
 public:
  PivotTurnSearch(SupportSearch& search, PivotTurnSettings settings = PivotTurnSettings());

  /// \brief A simple turn from the part at rest at `start` with base angle `start_theta` to
  ///        `goal`; not found (with the reason) when no pivot finger gives one within the
  ///        budget. `cancel`, when set and true, stops the search.
  SupportPath search(const Pose& start, double start_theta, const Pose& goal,
                     const std::atomic<bool>* cancel = nullptr);

  /// \brief The expansions of the next search().
  void setMaxExpansions(long expansions) { settings_.max_expansions = expansions; }
  /// \brief The wall time of the next search() [s].
  void setTimeLimit(double seconds) { settings_.time_limit = seconds; }
  const PivotTurnSettings& settings() const { return settings_; }

 private:
  /// \brief One search() in progress: its leads, lattice and best path, and its steps
  ///        (pivot_turn_search_run.h).
  class Run;
  /// \brief The rigid run from `from` (its set) to base angle `theta`, every angle_step at
  ///        most; empty when a waypoint is not valid.
  std::vector<SupportStep> rigidRun(const SupportStep& from, double theta);
  /// \brief The end of a simple turn from pivot waypoint `at`: the straight pivot to the
  ///        part angle psi and stroke l, then a rigid run to base angle theta; empty when none
  ///        is valid.
  std::vector<SupportStep> finish(const SupportStep& at, double psi, double theta, double l);

  SupportSearch& search_;
  PivotTurnSettings settings_;
};

}  // namespace rbsf::planner
