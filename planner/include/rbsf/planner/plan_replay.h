#pragma once
/// \file
/// \brief Verification of a plan by replaying it in the simulator, and the acceptance rule
///        of optimised plans (issue 5).
///
/// A replay runs round(duration / h) simulator steps of h from q0 at rest (a fresh
/// SimState), t_n = n h. The input of step n is
///   open loop:   tau_ff(t_n + h/2),
///   closed loop: TrackingController on (q(t_n), v(t_n)) against q_ref(t_n), v_ref(t_n)
///                with feed-forward tau_ff(t_n + h/2),
/// from the plan's reference trajectory (plan_reference.h). The midpoint makes a held
/// segment's tau exact (an open-loop replay of the planner's own plan repeats its
/// simulation bit for bit) and is the step's average of a ramp.
///
/// Reported (ReplayResult):
///   position_error  |(x, y) - (x_g, y_g)| at the end [m],
///   angle_error     |phi - phi_g*| at the end [rad], phi_g* the goal angle taken within pi
///                   of the reference's final angle (the turn the plan makes, "nearest" or
///                   "absolute"), phi not wrapped: ending a whole turn off counts 2 pi,
///   min_f_n         least normal force over all steps of the contacts not separated in
///                   that step [N] (0 when no contact ever touches),
///   phases          each of the plan's segments labelled by the majority of its steps'
///                   phases (an unsupported step counts as U; ties go to C, then P), the
///                   rule the planner labels its segments by (simulateSegments); then runs
///                   shorter than ReplaySettings::min_phase_run dropped and equal
///                   neighbours merged (filterPhaseRuns). A plan's own open-loop replay
///                   therefore gives plannedPhases(plan),
///   max_tracking_error  max over the steps of max_j |Theta_ref,j - Theta_j| at t_n, in
///                   the joints' own units (rad for theta, m for strokes; the numbers are
///                   compared as they are: 1 mm and 1 mrad weigh the same).
///   departure_time  the first t_n (or the end) at which the part's pose differs from the
///                   reference's by more than the position or the angle tolerance [s], -1
///                   if it never does; departure_phase the plan's phase there. Where a
///                   rejected plan first goes wrong: the final errors alone do not say.
///
/// Acceptance (acceptReplay): the closed-loop replay ends within the position and angle
/// tolerances of the goal (1 cm, 2 deg by default), has min_f_n >= 0, and its phase
/// sequence equals the plan's (plannedPhases: the segments' phases weighted by their
/// durations, filtered the same way), or is the plan's followed by one settling run: when
/// the plan brings the part to rest (its last sample's part speeds |x'|, |y'| [m/s] and
/// |phi'| [rad/s] all at most ReplaySettings::rest_speed, as optimised plans end) and ends
/// in U or P, the replay may end in one more run of a phase with more sticking contacts
/// (P or C after U, C after P). Contacts that slide to a stop stick under static friction
/// (mu_s > 0), so a part brought to rest in a U run is a C or P part for its last moments;
/// the planned sequence, which labels the run by its slides, cannot show that.

#include <string>
#include <vector>

#include "rbsf/dynamics/simulator.h"
#include "rbsf/dynamics/tracking_controller.h"
#include "rbsf/planner/plan.h"

namespace rbsf::planner {

/// \brief Settings of the replay and of the acceptance rule.
struct ReplaySettings {
  double min_phase_run = 0.02;                ///< phase runs shorter than this dropped [s]
  double position_tolerance = 0.01;           ///< accepted final COM error [m]
  double angle_tolerance = 2.0 * M_PI / 180;  ///< accepted final angle error [rad]
  /// \brief A plan whose last sample's part speeds are all at most this ends at rest, and
  ///        its replay may end in a settling run (file comment) [m/s, rad/s].
  double rest_speed = 1e-3;
  TrackingSettings tracking;  ///< gains of the closed loop
};

/// \brief Phase letters of consecutive runs (phase, duration [s]): runs shorter than
///        `min_run` dropped, then equal neighbours merged. When every run is short the
///        longest one is kept (a sequence is never empty for a non-empty input).
std::string filterPhaseRuns(const std::vector<std::pair<Phase, double>>& runs, double min_run);

/// \brief The plan's phase sequence by its segments (filterPhaseRuns on their durations).
std::string plannedPhases(const Plan& plan, double min_run);

/// \brief Replay `plan` open loop (controller null) or closed loop under `controller`.
/// \throws InputError when the plan has no segments or samples or its q0 does not fit
///         the simulator's model.
ReplayResult replayPlan(const Simulator& simulator, const Plan& plan,
                        const TrackingController* controller, const ReplaySettings& settings);

/// \brief The acceptance rule of the file comment; `reason` (when given) receives why a
///        replay is rejected, naming each failed criterion and by how much.
bool acceptReplay(const Plan& plan, const ReplayResult& closed_loop, const ReplaySettings& settings,
                  std::string* reason = nullptr);

/// \brief "leaves the planned path at t = <t> s (planned phase <X>)" for a replay that left
///        it (departure_time >= 0), "" otherwise: the one wording of the rejection reason
///        and of plan-reorientation's replay lines.
std::string departureText(const ReplayResult& result);

/// \brief Both replays and the verdict (the tracking controller tuned at q0).
ReplaySummary verifyPlan(const Simulator& simulator, const Plan& plan,
                         const ReplaySettings& settings, std::string* reason = nullptr);

}  // namespace rbsf::planner
