#pragma once
/// \file
/// \brief What a certificate says (certificate.h): how each closed-loop trial of a plan
///        ended and the verdict over all of them. Plain data, written into plan files
///        (plan.h key `certificate`) and by rbsf-replay.

#include <cstdint>
#include <string>

#include <string_view>
#include "rbsf/dynamics/control/execution_status.h"

#include "rbsf/dynamics/core/sensing.h"
#include "rbsf/plan/plan_holding.h"
#include "rbsf/plan/plan_motion.h"

namespace rbsf::plan {

/// \brief How one trial ended. Poses are the part's frame as the plan knows it (a drawn
///        COM offset does not move the goal).
struct TrialOutcome {
  int index = -1;               ///< trial number, from 0
  bool success = false;         ///< every criterion of certificate.h met
  std::string failure;          ///< the failed criteria with their values; empty on success
  double position_error = 0.0;  ///< final distance to the goal position [m]
  double angle_error = 0.0;     ///< final |phi - phi_goal| [rad]
  double speed = 0.0;           ///< mean part speed over the last rest window [m/s]
  double angular_speed = 0.0;   ///< mean |phi'| over the last rest window [rad/s]
  bool dropped = false;         ///< the part left the fingers, was lost or the state diverged
  double dropped_time = -1.0;   ///< when [s]; -1 if never
  double saturated_time = 0.0;  ///< time the law demanded more than an input's limit [s]
  double min_f_n = 0.0;         ///< least normal force of a touching contact [N]
  /// \brief Largest distance from the plan's path in tolerance units: max over the trial of
  ///        max(position distance / position tolerance, angle distance / angle tolerance).
  double max_deviation = 0.0;
  std::string phases;            ///< phase sequence seen (runs under min_phase_run dropped)
  double departure_time = -1.0;  ///< first time farther from the path than a tolerance [s]
  std::string departure_phase;   ///< the plan's phase letter there ("hold" after its end)
  /// \brief What the execution status (plan_executor.h) said over the trial: its largest
  ///        deviations of the part [m, deg] and of a relied-on stroke [m] and its rate
  ///        [m/s], the first time
  ///        its verdict was leaving (-1: never), the hold it made (kNone: none) and when,
  ///        and its last verdict.
  double status_position = 0.0;
  double status_angle = 0.0;
  double status_stroke = 0.0;
  double status_stroke_speed = 0.0;
  double leaving_time = -1.0;
  HoldReason hold = HoldReason::kNone;
  double hold_time = -1.0;
  ExecutionVerdict final_verdict = ExecutionVerdict::kOnPlan;
  /// \brief Faults drawn (trial.h): the first time one acted (-1: none), and the first time
  ///        at or after it that the status flagged one (-1: never).
  double fault_time = -1.0;
  double fault_seen_time = -1.0;
  /// \brief The first time the status said leaving or holding (-1: never): a drop reported
  ///        no later than 50 ms after it happened counts as reported.
  double report_time = -1.0;
};

/// \brief How a trial ended: done (succeeded, never held), held (a hold kept the part on the
///        fingers), lost (dropped) or off (ended unheld away from the goal or not at rest).
enum class TrialEnd : std::uint8_t { kDone, kHeld, kLost, kOff };
/// \brief The end of `o`.
TrialEnd trialEnd(const TrialOutcome& o);
/// \brief "done", "held", "lost", "off".
const char* toString(TrialEnd end);

/// \brief The control law a certificate's trials ran (certificate.h): the plan's law with
///        part feedback, with joint feedback only, or the plan's inputs open loop.
enum class TrialLaw { kPartFeedback, kJointFeedback, kOpenLoop };

/// \brief "part feedback", "joint feedback" or "open loop", the words of plan files.
const char* toString(TrialLaw law);
/// \brief The law named `name` (toString's words). \throws InputError naming `where`.
TrialLaw parseTrialLaw(std::string_view name, const std::string& where);

/// \brief The verdict over a set of trials (certificate.h).
struct Certificate {
  bool ran = false;
  TrialLaw law = TrialLaw::kPartFeedback;
  int trials = 0;  ///< trials run and counted
  int successes = 0;
  double success_rate = 0.0;  ///< successes / trials
  /// \brief The one-sided Clopper-Pearson lower bound of the success rate at `confidence`
  ///        (confidence.h).
  double lower_bound = 0.0;
  double confidence = 0.95;
  /// \brief Certified when lower_bound >= this, motion.ok() and, when holding_required,
  ///        holding.ok().
  double required_rate = 0.95;
  bool certified = false;
  /// \brief The trials ran in batches until the bound decided (certificate.h); false: a
  ///        fixed count.
  bool sequential = false;
  int batch = 0;                    ///< sequential: trials between two looks at the bound
  int max_trials = 0;               ///< sequential: the cap on trials
  std::uint64_t seed = 0;           ///< the draws' seed: the same seed gives the same certificate
  double settle_time = 0.0;         ///< held at rest after the plan's end [s]
  double position_tolerance = 0.0;  ///< [m]
  double angle_tolerance = 0.0;     ///< [rad]
  double rest_speed = 0.0;          ///< [m/s]
  double rest_angular_speed = 0.0;  ///< [rad/s]
  Sensing sensing;                  ///< what the trials' cell measured
  Uncertainty uncertainty;          ///< what they drew from
  TrialOutcome worst;               ///< the worst trial (certificate.h), index -1 when none
  PlanMotion motion;                ///< the plan's speeds against the cell's motion limits
  bool holding_required = false;    ///< the law feeds back the joints only
  PlanHolding holding;              ///< whether the joints alone fix the part (when required)
};

/// \brief The certificate as JSON text (the plan file's `certificate` object, plan.h).
std::string certificateJsonText(const Certificate& certificate);

/// \brief The worst trial in metres and degrees: "trial 7: ends 0.0135 m and 1.03 deg from
///        the goal, moving 0.0088 m/s and 2.6 deg/s; left the planned path at t = 0.421 s
///        (planned phase U); phases CPU" (and "dropped at t = ..." when it was).
std::string worstTrialText(const Certificate& certificate);

/// \brief The report a tool prints: "certificate (<law>, <N> trials, seed <S>): CERTIFIED" or
///        "NOT CERTIFIED", the successes and the bound (ratesText), for a sequential
///        certificate how it stopped (stopText), the worst trial (worstTrialText) and, when
///        it failed, why; then the plan's motion (motionText) and, when required, its
///        holding (holdingText). Lines end in newlines.
std::string certificateReportText(const Certificate& certificate);

/// \brief The successes and the bound: "64/64 trials succeeded (100 %; 95 % lower confidence
///        bound 0.954 >= 0.95 required)" (">=" or "<"; the bound rounded down, so that the
///        comparison reads true).
std::string ratesText(const Certificate& certificate);

/// \brief How a sequential certificate stopped: "sequential, batches of 64 up to 512
///        trials: stopped after 64, the bound reached the required rate" (or "... after 192:
///        even 320 more successes would leave the bound below the required rate", "... the
///        cap reached", "... after 64: the plan fails its motion limits or holding, whatever
///        the trials"); empty for a fixed count.
std::string stopText(const Certificate& certificate);

/// \brief The one-line verdict: "certified: <ratesText>" or "NOT certified: <ratesText>;
///        worst trial 7: <its failure>" (and "; the plan <motionViolationText>" when the
///        plan breaks the motion limits, "; the joints alone do not hold the part ..." when
///        its holding is required and fails).
std::string verdictText(const Certificate& certificate);

}  // namespace rbsf::plan
