#pragma once
/// \file
/// \brief A path of quasi-static supports from a start pose to a goal pose: the part
///        carried slowly enough that at every instant it is in balance on its contacts,
///        with margins, and (by default) held by the joints alone (support_geometry.h).
///
/// Search: weighted A* over continuous support states kept one per lattice cell (hybrid
/// A*), from both ends at once: one tree grows from the start, one from the goal's supports
/// at candidate base angles (every `goal_theta_step` within the limits, psi the goal angle
/// +- 2 pi), taking turns; quasi-static moves are reversible, so the goal tree read
/// backwards runs to the goal. A state is a JigPose, a contact set and, for a pivot, its
/// anchor. Moves:
///   - **slide** (every touching contact slides, frictionless when mu_k = 0): a step of
///     `xy_step` in X or Y, `angle_step` in psi or theta, or psi with theta or X;
///   - **pivot** about the sticking finger k (its tip keeps its point of the part): a step
///     in psi, theta or both, or of the pivot's stroke;
///   - **rigid** (two or more stick): the base turns a step, or every finger strokes alike;
///   - **switch** at a fixed pose: every contact slides, one or all stick, a finger touches
///     or lets go.
/// A move is taken when the support is valid at its end and its midpoint, with the slip
/// the move makes (kinetic friction). Cost: the move's normalised length (metres over
/// `length_scale`, radians as they are) times 1 + margin_weight / (margin + 0.01), plus
/// `switch_cost` for a switch, so the path keeps away from the margins' edges and changes
/// contacts seldom. States are kept one per cell of (psi, theta, X) and contact set: the
/// part's height Y changes no balance, only the strokes. The path is found when a sliding
/// state of one tree reaches one of the other's with the same fingers by a straight slide,
/// when a pivot of one tree reaches a nearby pivot of the other on another finger by a
/// pivot, a hand-over of the stick and a pivot (a bridge: the boundary point the second
/// finger must hold fixes the part angle of the hand-over; checked every step), or when a
/// start-tree state reaches the goal by a straight slide or by the pivot that puts the part
/// on it (the anchor fixes the stroke and the base angle in closed form). A path found is a
/// candidate: the search goes on for `search_on` times the expansions the first took, and
/// keeps the path with the fewest phase runs (contact sets in a row), then the shortest, as
/// a cell engineer would (every run starts and ends at rest, so each costs time and risk).
///
/// **Breakaway.** Every run rests at its ends, so its sliders start out stuck: a run with
/// sliding contacts is entered only where they break away first
/// (SupportGeometry::breaksAway, with the first move's slip). The start tree checks its
/// first move after a root or a switch; the goal tree, whose moves run backwards in time,
/// checks a node before it switches away from it (the run then starts there, towards the
/// node it came from).
///
/// Cells blocked with block() (a cell of the lattice with a contact set) are never entered,
/// by a move, a root or the straight slides and pivots that join the trees, in this and
/// later searches: the support planner blocks the stretches whose closed-loop runs failed.
///
/// Deterministic: the same inputs give the same path. Analysis-time code (allocates).

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "rbsf/planner/support/support_geometry.h"

namespace rbsf::planner {

/// \brief One waypoint of a support path.
struct SupportStep {
  JigPose pose;
  ContactSet set;
  PivotAnchor anchor;   ///< meaningful when set.pivot() >= 0
  VecQ q;               ///< configuration (state_layout.h)
  double margin = 0.0;  ///< balance margin of the step's support
  /// \brief The part rests here before moving on: a root or a contact switch, or a move
  ///        from rest that slips no slider more than 0.1 mm (the start tree's sense of time).
  bool rest = false;
};

/// \brief Whether some sliding contact of `set` slips more than kSlipStep in `slip`
///        (SupportGeometry::slipDirections).
bool slidersSlip(const ContactSet& set, const VecC& slip);

/// \brief Phase runs of a path: 1 plus the changes of contact set between waypoints.
int phaseRuns(const std::vector<SupportStep>& steps);
/// \brief Length of a path in the searches' metric (poseDistance).
double pathLength(const std::vector<SupportStep>& steps, double length_scale);

/// \brief Settings of SupportSearch (file comment).
struct SupportSearchSettings {
  double angle_step = 0.05;   ///< [rad] (about 3 deg)
  double xy_step = 0.01;      ///< [m]
  double length_scale = 0.1;  ///< metres per unit of cost [m]
  double switch_cost = 1.0;
  double margin_weight = 0.05;
  double heuristic_weight = 2.0;    ///< weighted A* (>= 1)
  double goal_connect = 0.6;        ///< try the straight slide below this heuristic
  double goal_theta_step = 0.0873;  ///< [rad] (5 deg)
  /// \brief After the first path, search on for this many times the expansions it took,
  ///        keeping the path with the fewest phase runs, then the shortest (0: the first).
  double search_on = 1.0;
  long max_expansions = 400000;
  double time_limit = 30.0;  ///< wall time [s] (infinity: none)
  SupportSettings support;
};

/// \brief The searches' cost of the move from `a` to `b`: its length (poseDistance over
///        `s.length_scale`) times 1 + margin_weight / (the lower margin of its ends + 0.01).
double moveCost(const SupportStep& a, const SupportStep& b, const SupportSearchSettings& s);

/// \brief Outcome of SupportSearch::search().
struct SupportPath {
  bool found = false;
  std::vector<SupportStep> steps;  ///< start to goal
  long expansions = 0;
  std::string message;  ///< why nothing was found
  SupportReach reach;   ///< what the start tree reached (support_reach.h)
};

/// \brief The search of the file comment; one per thread.
class SupportSearch {
 public:
  SupportSearch(const RbsfModel& model, SupportSearchSettings settings);

  /// \brief A path from the part at rest at `start` with base angle `start_theta` to
  ///        `goal` (any base angle). `cancel`, when set and true, stops the search.
  SupportPath search(const Pose& start, double start_theta, const Pose& goal,
                     const std::atomic<bool>* cancel = nullptr);

  /// \brief The straight slide from `from` (its contact set) to `to`: its waypoints, every
  ///        angle_step / xy_step, or an empty vector when a waypoint is not valid.
  std::vector<SupportStep> straightSlide(const SupportStep& from, const JigPose& to);

  /// \brief The straight pivot from `from` to part angle psi, base angle theta and pivot
  ///        stroke `stroke`, or an empty vector (as straightSlide).
  std::vector<SupportStep> straightPivot(const SupportStep& from, double psi, double theta,
                                         double stroke);

  /// \brief Keep later searches out of `step`'s lattice cell with its contact set, and out
  ///        of the cells up to `radius` steps from it in psi, theta and X with that set (a
  ///        stretch that cannot be run).
  void block(const SupportStep& step, int radius = 0);
  /// \brief The wall time of the next search() [s].
  void setTimeLimit(double seconds) { settings_.time_limit = seconds; }
  /// \brief The expansions of the next search().
  void setMaxExpansions(long expansions) { settings_.max_expansions = expansions; }
  /// \brief Cells blocked so far.
  std::size_t blockedCount() const { return blocked_.size(); }

  /// \brief The part at rest at `pose` on `set` (a root of a search), into `out`; false
  ///        when the support is not valid there or a pivot's finger does not hold the part.
  bool restAt(const JigPose& pose, const ContactSet& set, SupportStep& out);
  /// \brief The anchor of a pivot set at `pose` (the tip where it touches); true without
  ///        a pivot.
  bool anchorFor(const JigPose& pose, const ContactSet& set, PivotAnchor& anchor);
  /// \brief The support of `set` at `pose` reached from `from` (a move when the sets are
  ///        equal, else a switch at rest); false when it is blocked or not valid, or when a
  ///        move from rest does not break away. `backward`: the move extends the goal tree,
  ///        so it runs backwards in time and starts no run (the caller checks breakaway).
  ///        On false, refusal_ holds the rule broken.
  bool stepTo(const SupportStep& from, const JigPose& pose, const ContactSet& set,
              const PivotAnchor& anchor, SupportStep& out, bool backward = false);
  /// \brief Why the last stepTo() refused.
  SupportRule refusal() const { return refusal_; }

  SupportGeometry& geometry() { return geometry_; }
  const SupportSearchSettings& settings() const { return settings_; }

 private:
  /// \brief A node of a search tree (support_search_run.h).
  struct Node;
  /// \brief One search() in progress: its trees, open lists and best path, and its steps
  ///        (support_search_run.h).
  class Run;
  /// \brief A lattice cell and a contact set.
  using CellKey = std::array<std::int32_t, 6>;
  /// \brief FNV-1a over a CellKey.
  struct CellKeyHash {
    std::size_t operator()(const CellKey& k) const;
  };
  /// \brief The lattice cell of a pose and a contact set (states are kept one per key).
  CellKey key(const JigPose& pose, const ContactSet& set) const;
  const RbsfModel& model_;
  SupportSearchSettings settings_;
  SupportGeometry geometry_;
  std::unordered_set<CellKey, CellKeyHash> blocked_;
  SupportRule refusal_ = SupportRule::kBalance;  ///< why the last stepTo() refused
};

}  // namespace rbsf::planner
