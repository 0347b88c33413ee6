#pragma once
/// \file
/// \brief Simple turns: the part turned by as few pivots as the cell allows, the way a cell
///        engineer would turn it by hand, found before the general support search
///        (support_search.h) is tried.
///
/// A simple turn is a chain of runs, each from rest to rest:
///   - **rigid** runs: two or more tips stick and the base turns;
///   - **pivots** about a finger k: its tip keeps its point xi_k of the part at stroke l_k,
///     the other touching tips slide (at most `max_sliders`: by default one, every other
///     finger lifted), and the part angle psi, the base angle theta and the stroke l_k all
///     change along the run. One pivot is one run: it does not stop on the way (a slider
///     that would turn back is a rest, and a rest ends the pivot);
///   - between runs, at rest, fingers let go or touch and the sticking tips change: lift
///     first, then break loose.
/// The last pivot ends where its anchor puts the part on the goal: the tip's world point on
/// the goal pose fixes the stroke and the base angle (SupportGeometry::pivotOnto), so the
/// pivot ends at that part angle and stroke, then rests and a rigid run turns the base onto
/// the goal's angle.
///
/// Search: weighted A* over support states kept one per lattice cell of (psi, theta, X, Y)
/// with steps `angle_step` and `xy_step`, the contact set and the pivots so far, from the
/// start at rest on every valid set of its placed fingers. Moves: a pivot's 26 lattice
/// neighbours in (psi, theta, l_k) (`stroke_step`), a rigid run's base step, and the
/// switches of contact set at rest (a new pivot set starts a pivot: at most `max_pivots`).
/// Each is taken when its end support is valid with the move's slip and, from rest, breaks
/// away (SupportSearch::stepTo: the balance and the contact-force law's own check). Cost:
/// the support search's (metres over `length_scale`, radians as they are, weighted by the
/// margin), `switch_cost` a switch and `pivot_cost` a pivot; heuristic: the world pose's
/// distance to the goal. The pivots are deepened one at a time (a search with at most 1,
/// then 2, ...), so the path found has the fewest pivots; among the paths found within
/// `search_on` times the expansions of the first, the one with the fewest phase runs, then
/// the shortest, is kept.
///
/// Cells blocked in the SupportSearch are not entered here either. Deterministic: the same
/// inputs give the same path, and a budget in expansions gives it on any machine where the
/// time limit does not bind first. Analysis-time code (allocates).

#include <atomic>
#include <cstdint>
#include <vector>

#include "rbsf/planner/support/support_search.h"

namespace rbsf::planner {

/// \brief Settings of PivotTurnSearch (file comment).
struct PivotTurnSettings {
  double angle_step = 3.75 * M_PI / 180;  ///< psi and theta lattice [rad]
  double stroke_step = 0.015;             ///< a pivot's stroke step [m]
  double xy_step = 0.01;                  ///< the lattice of the part's X and Y [m]
  double heuristic_weight = 2.0;          ///< weighted A* (>= 1)
  double pivot_cost = 1.0;                ///< added for each pivot, beside switch_cost
  int max_pivots = 3;                     ///< pivots of a simple turn at most
  /// \brief Sliding tips of a pivot at most: 1 lifts every other finger, so that the pivot's
  ///        two tips (at different heights) let the finger forces steer their squeeze and
  ///        pull the slider loose; a pivot with more sliders is taken only where the law's
  ///        check (SupportSettings::law_check) passes at its start and along it.
  int max_sliders = 1;
  long max_expansions = 60000;  ///< lattice nodes expanded, every depth together
  double time_limit = 30.0;  ///< wall time [s] (infinity: none); the budget above is the machine's
};

/// \brief The number of pivots of a path: its runs whose set has exactly one sticking contact.
int pivotRuns(const std::vector<SupportStep>& steps);

/// \brief The sets a simple turn may switch to at rest among the fingers of `reach` (of m):
///        two or more touching, all sticking (rigid) or one sticking with at most
///        `max_sliders` sliding (a pivot).
std::vector<ContactSet> restSetsWithin(std::uint32_t reach, int m, int max_sliders);

/// \brief The search of the file comment; one per thread. Uses `search`'s geometry, steps,
///        blocked cells and cost settings.
class PivotTurnSearch {
 public:
  PivotTurnSearch(SupportSearch& search, PivotTurnSettings settings = PivotTurnSettings());

  /// \brief A simple turn from the part at rest at `start` with base angle `start_theta` to
  ///        `goal`; not found (with the reason) when none is within the budget. `cancel`,
  ///        when set and true, stops the search.
  SupportPath search(const Pose& start, double start_theta, const Pose& goal,
                     const std::atomic<bool>* cancel = nullptr);

  /// \brief The expansions of the next search().
  void setMaxExpansions(long expansions) { settings_.max_expansions = expansions; }
  /// \brief The wall time of the next search() [s].
  void setTimeLimit(double seconds) { settings_.time_limit = seconds; }
  const PivotTurnSettings& settings() const { return settings_; }

 private:
  /// \brief One search() in progress: its lattice, open list and best path, and its steps
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
