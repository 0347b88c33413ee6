#pragma once
/// \file
/// \brief A support path (support_search.h) made into motion: slow, rest-to-rest runs and
///        force hand-overs at rest, as a reference with the feed-forward input of each
///        instant; then run once closed loop on the nominal cell, which makes the plan.
///
/// **Runs.** Consecutive waypoints with one contact set form a run. The part moves along
/// the run's waypoints, interpolated by a Catmull-Rom spline in the run's coordinates
/// ((X, Y, psi, theta) sliding, (psi, theta, l_k) pivoting, (theta, Y) rigid), timed by
/// the quintic rest-to-rest law s(t) = 10 u^3 - 15 u^4 + 6 u^5 (peak rate 1.875 x the
/// mean), slow enough that the part's speed stays below `part_speed`, its and the base's
/// angular speed below `angular_speed`, the strokes' below `stroke_speed`, and every peak
/// acceleration below `part_acceleration` (m/s^2, rad/s^2 alike). Where a run's spline
/// leaves the jig between valid waypoints (it overshoots at corners), the run is split: the
/// part rests at the waypoints around that interval and crosses it on a straight line, the
/// motion the search checked.
///
/// **Settling.** The reference starts with the part at rest for `settle_time` under the
/// input of the first set's balance, and ends with it at rest for `end_rest` under the last
/// set's.
///
/// **Hand-overs.** Between runs the part rests while the contact forces go from one set's
/// to the next's: a finger that joins first rises (rest to rest) to the point where it
/// touches and rests there for `touch_time` (the law raises it on until it meets the part),
/// then the forces ramp over `handover_time`; a finger that leaves is first
/// unloaded by the ramp, then lowered to its stroke limit.
///
/// **Feed-forward.** At each knot (every `knot_interval`) q, v and dv/dt of the motion
/// (central differences of the geometry) and the input of the set's contact balance
/// (contact_balance.h: the margin-maximising forces that carry that motion); the input
/// ramps between knots.
///
/// **The plan.** The reference is run once, closed loop with the control law on the exact
/// state of the nominal cell (control_law.h computeFromState, every 5 ms, held), and the
/// inputs are recorded: the plan is that trajectory, exact (its segments re-simulated reproduce
/// it), with the phases the simulator took. Every support holds the part by the joints
/// alone, so the plan's law feeds back the joints (Plan::joint_feedback).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/control/reference_trajectory.h"
#include "rbsf/dynamics/core/sensing.h"
#include "rbsf/plan/plan.h"
#include "rbsf/planner/support/support_search.h"

namespace rbsf::planner {

/// \brief Speeds and times of the motion (file comment); SI units.
struct SupportTiming {
  double part_speed = 0.08;         ///< [m/s]
  double angular_speed = 0.35;      ///< part and base [rad/s]
  double stroke_speed = 0.08;       ///< [m/s]
  double part_acceleration = 0.25;  ///< [m/s^2] and [rad/s^2]
  double handover_time = 0.3;       ///< [s]
  double min_run_time = 0.3;        ///< [s]
  double knot_interval = 0.01;      ///< [s]
  /// \brief The part rests this long at the start under the first set's forces [s]: a part
  ///        placed a little off lets its contacts settle before the first run (0.5 and 1 s
  ///        hold 230 of 256 certificate trials of the 15 and 30 degree plans, none 221).
  double settle_time = 0.5;
  /// \brief The part rests this long at the end under the last set's forces [s], so that the
  ///        plan, run closed loop, ends at rest.
  double end_rest = 0.3;
  /// \brief A finger that joins rests at its planned stroke this long before the forces
  ///        ramp onto it [s], while the law raises it until it meets the part
  ///        (ContactReading::join_reach): the part may lie higher than planned.
  double touch_time = 1.0;
};

/// \brief One stretch of the reference: a run or a hand-over.
struct SupportRun {
  double start = 0.0, end = 0.0;  ///< [s]
  ContactSet set;                 ///< the set that carries the part
  bool handover = false;          ///< forces change at rest (or a finger moves alone)
  /// \brief The path's steps it covers: a run's waypoints; a hand-over's two steps at the
  ///        pose where the sets change.
  std::size_t first_step = 0, last_step = 0;
};

/// \brief A stretch whose motion leaves the jig between waypoints that are within it (a
///        touching tip's line misses the part or meets it too obliquely), even straight.
class SupportReferenceError : public std::runtime_error {
 public:
  SupportReferenceError(std::size_t first, std::size_t last);
  std::size_t first_step, last_step;  ///< the stretch's steps (SupportRun)
};

/// \brief The reference of a support path (file comment); `runs`, when given, receives its
///        stretches. \throws std::invalid_argument for an empty path,
///        SupportReferenceError for a stretch that leaves the jig.
ReferenceTrajectory supportReference(const RbsfModel& model, SupportGeometry& geometry,
                                     const SupportPath& path, const SupportTiming& timing,
                                     std::vector<SupportRun>* runs = nullptr);

/// \brief The time of the first sample of `plan` whose part pose is more than `position`
///        [m] from `reference`'s or more than `angle` [rad] turned from it; negative when
///        none is.
double departureTime(const plan::Plan& plan, const ReferenceTrajectory& reference, double position,
                     double angle);

/// \brief Run `reference` closed loop on the nominal cell (the joint law on the exact state,
///        evaluated every `control_steps` simulator steps and held) and record it as a plan
///        with joint_feedback set: a segment per evaluation, samples every `sample_steps`
///        steps, status "exact" when the part ends within the tolerances (position [m],
///        angle [rad]) of `goal`. A run whose part falls off (fellOff, rollout.h) stops there.
plan::Plan closedLoopPlan(const RbsfModel& model, const ReferenceTrajectory& reference,
                          const SimulatorSettings& simulator, const FeedbackSettings& feedback,
                          const Pose& goal, double position_tolerance, double angle_tolerance,
                          int sample_steps, int control_steps = 5);

}  // namespace rbsf::planner
