#pragma once
/// \file
/// \brief The support planner as one call: a support path (support_search.h), its motion
///        and the exact plan that motion makes closed loop (support_trajectory.h).
///
/// The plan handles the part slowly and keeps it in balance with margins at every instant;
/// the joints alone hold it (Plan::joint_feedback), so its law feeds back the joints. The
/// goal angle is reached the shorter way (or +- 2 pi when that way has no path). Status
/// "exact" when the closed-loop run ends within the tolerances of the goal.
///
/// Simple turns (one pivot, pivot_turn_search.h) are searched first when asked for, then the
/// general search (support_search.h) at each friction use in turn.
///
/// A balanced support is not always one the joints can hold: where the touching contacts
/// barely fix the part, the nominal closed-loop run leaves the reference with the strokes
/// on theirs. So each path found is run before it is accepted (a lazy check, like a lazy
/// roadmap's edges): when the run misses the goal, the stretch where it first departed from
/// the reference (or the last, when it never did), or a stretch whose motion leaves the
/// jig, has its cells blocked (SupportSearch::block) and the search runs again, until a
/// run ends on the goal, `max_paths` were run or the time is up. Without such a run, the
/// plan of the path that followed its reference longest is returned (status approximate).

#include <atomic>
#include <string>
#include <vector>

#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/plan/plan.h"
#include "rbsf/plan/plan_margins.h"
#include "rbsf/planner/planner_settings.h"
#include "rbsf/planner/support/pivot_turn_search.h"
#include "rbsf/planner/support/support_trajectory.h"

namespace rbsf::planner {

/// \brief Settings of SupportPlanner.
struct SupportPlannerSettings {
  SupportSearchSettings search = defaultSearch();
  SupportTiming timing;
  FeedbackSettings feedback;    ///< the law of the closed-loop run
  SimulatorSettings simulator;  ///< the plan's physics
  double time_limit = 30.0;     ///< search wall time, all attempts [s] (infinity: none)
  /// \brief Expansions of all the searches together (0: no bound). A budget in expansions
  ///        gives the same plan on any machine, under any load, where the time limit does not
  ///        bind first.
  long max_expansions = 0;
  /// \brief The sticking forces' share of the friction cone (BalanceSettings::friction_use)
  ///        of each search attempt, the strongest margin first: the next is tried when an
  ///        attempt ends without a path whose run ends on the goal.
  std::vector<double> friction_uses = {0.45, 0.6};
  /// \brief The friction uses at which simple turns (pivot_turn_search.h) are searched,
  ///        before any general search (default none: on the default cell their pivots slide
  ///        two tips at once, which the contact-force law does not yet carry from rest, so
  ///        they add search time without a certified plan).
  std::vector<double> simple_turn_friction_uses;
  PivotTurnSettings simple_turn;  ///< the simple turns' lattice and budget
  /// \brief The nominal run departs when the part is this far from the reference [m]...
  ///        (half the goal tolerances; the certified 30 degree plan's run stays within
  ///        0.9 mm and 0.42 deg of its reference)
  double departure_position = 0.005;
  /// \brief ... or turned this far from it [rad].
  double departure_angle = 1.0 * M_PI / 180;
  /// \brief Lattice steps (psi, theta, X) blocked around a departed stretch's waypoints.
  int block_radius = 1;
  int max_paths = 40;     ///< paths run per friction use (at least 1)
  int sample_steps = 20;  ///< plan samples every this many steps

  /// \brief The search's defaults for the support planner: 5 deg and 2 cm steps, greedy
  ///        (weight 5), sliding normals up to 84 deg from the finger's axis.
  static SupportSearchSettings defaultSearch();
};

/// \brief Plans with supports; one per thread.
class SupportPlanner {
 public:
  SupportPlanner(const RbsfModel& model, SupportPlannerSettings settings);

  /// \brief Search, then make the plan, until a run ends on the goal, the budget is spent
  ///        or `cancel` (when given) is true. False (plan empty) when no support path was
  ///        found: message() says why.
  bool solve(const Problem& problem, plan::Plan& plan, const std::atomic<bool>* cancel = nullptr);

  /// \brief Why the last solve() found nothing, empty otherwise.
  const std::string& message() const { return message_; }
  /// \brief Expansions of the last solve(), every attempt.
  long expansions() const { return expansions_; }
  /// \brief The friction use of the attempt that found the path (0 when none did).
  double frictionUse() const { return friction_use_; }
  /// \brief The margins the last solve()'s plan was planned with, for its refinement: a
  ///        support plan, frictionUse() and the balance's normal margin.
  plan::PlanMargins margins() const;
  /// \brief Paths found and run by the last solve(), every attempt.
  int pathsRun() const { return paths_; }
  /// \brief What the last solve()'s searches reached, merged (support_reach.h): the answer
  ///        to give when none found a path.
  const SupportReach& reach() const { return reach_; }
  const SupportPlannerSettings& settings() const { return settings_; }

 private:
  class Run;  ///< one solve()'s state (support_planner.cpp)

  const RbsfModel& model_;
  SupportPlannerSettings settings_;
  std::string message_;
  long expansions_ = 0;
  double friction_use_ = 0.0;
  int paths_ = 0;
  SupportReach reach_;
};

}  // namespace rbsf::planner
