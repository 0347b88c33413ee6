#pragma once
/// \file
/// \brief How one execution of a plan is going, tick by tick (plan_executor.h fills it): the
///        part's deviation from the plan, each contact's planned role against the estimated
///        one, the inputs' saturation, the sensors' health and a verdict; and the limits
///        that turn those measures into the verdict.
///
/// Verdicts, in order of precedence:
///   kHolding   the reference is stopped and the part held where it is (hold_reason says
///              why: the run was leaving, a fault lasted, or the cell asked);
///   kLeaving   the part is off the plan's tube: its deviation beyond the leaving band, a
///              relied-on finger's stroke or stroke rate beyond leaving_stroke or
///              leaving_stroke_speed (a finger that loses the part's load accelerates
///              at tens of m/s^2), or a relied-on contact open for contact_open_time;
///   kDone      the plan has ended and the part rests within the degraded band;
///   kDegraded  on the tube but not as planned: a deviation beyond the degraded band, an
///              input at its limit, a stale part pose, a bad reading bridged, a late tick,
///              a sticking tip slipping, a planned slider stuck for slider_stuck_time;
///   kOnPlan    none of these.

#include <cmath>
#include <cstdint>
#include <string>

#include "rbsf/dynamics/core/contact_roles.h"
#include "rbsf/dynamics/core/mode_dynamics.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief The verdict of one tick (file comment).
enum class ExecutionVerdict : std::uint8_t { kOnPlan, kDegraded, kLeaving, kHolding, kDone };

/// \brief Why the part is held.
enum class HoldReason : std::uint8_t {
  kNone,       ///< not held
  kLeaving,    ///< the run was leaving the plan's tube
  kBadJoints,  ///< joint readings were not finite for longer than bad_joint_time
  kStalePose,  ///< a part-feedback run had no part pose for longer than stale_pose_hold
  kBadOutput,  ///< the law's input was not finite (the last good input was applied)
  kCommanded   ///< the cell asked (hold())
};

/// \brief What a tick found wrong (bits of ExecutionStatus::flags).
enum ExecutionFlag : std::uint32_t {
  kFlagDeviation = 1u << 0,     ///< deviation beyond the degraded band
  kFlagOffTube = 1u << 1,       ///< deviation or stroke beyond the leaving band
  kFlagContactOpen = 1u << 2,   ///< a relied-on contact open in the estimate
  kFlagSliderStuck = 1u << 3,   ///< a planned slider stuck for slider_stuck_time
  kFlagTipSlipping = 1u << 4,   ///< a planned sticking tip slipping in the estimate
  kFlagSaturated = 1u << 5,     ///< an input at its limit
  kFlagStalePose = 1u << 6,     ///< the newest part pose is older than stale_pose_time
  kFlagBadJoints = 1u << 7,     ///< this tick's joint reading was not finite (bridged)
  kFlagBadPose = 1u << 8,       ///< a part pose since the last tick was not finite (dropped)
  kFlagBadTime = 1u << 9,       ///< this tick's time was not finite (the last input held)
  kFlagStrokeError = 1u << 10,  ///< a relied-on stroke or its rate beyond the degraded band
  kFlagLateTick = 1u << 11,     ///< this tick came more than 1.5 periods after the last
  kFlagJointJump = 1u << 12,    ///< this tick's joint reading jumped (a spike; bridged)
};

/// \brief "on plan", "degraded", "leaving", "holding", "done".
const char* toString(ExecutionVerdict verdict);
/// \brief "none", "leaving", "bad joints", "stale pose", "bad output", "commanded".
const char* toString(HoldReason reason);
/// \brief The flags set in `flags` as words ("; deviation, input at its limit"), "" when
///        none. Allocates: for reports, not the loop.
std::string flagsText(std::uint32_t flags);

/// \brief The bands and times of the verdict (file comment). The defaults sit above what
///        certified runs of the default cell reach under the cell's noise and uncertainty
///        (so a sound run does not raise a false alarm) and below what a part sliding off
///        reaches within a few ticks (so a real one is caught while it can still be held).
struct ExecutionLimits {
  double degraded_position = 0.01;             ///< part position deviation [m]
  double degraded_angle = 2.0 * M_PI / 180.0;  ///< part angle deviation [rad]
  double leaving_position = 0.03;              ///< [m]
  double leaving_angle = 8.0 * M_PI / 180.0;   ///< [rad]
  double degraded_stroke = 0.01;        ///< a relied-on finger's stroke from its reference [m]
  double leaving_stroke = 0.03;         ///< [m]
  double degraded_stroke_speed = 0.05;  ///< its rate from the reference's [m/s]
  double leaving_stroke_speed = 0.3;    ///< [m/s]
  double contact_open_time = 0.02;      ///< a relied-on contact open this long: leaving [s]
  double slider_stuck_time = 0.3;       ///< a planned slider stuck this long: degraded [s]
  /// \brief A part pose is stale when its stamp is older than this [s] (the sensor's
  ///        latency plus a few periods).
  double stale_pose_time = 0.06;
  /// \brief A part-feedback run holds when its newest pose is older than this [s].
  double stale_pose_hold = 0.3;
  /// \brief Non-finite joint readings are bridged by the last good one for at most this
  ///        long [s]; then the part is held (still on the last good reading).
  double bad_joint_time = 0.02;
  /// \brief A reading that jumps from its prediction by more than this times the largest
  ///        move its actuator can make in a period is a spike (plan_executor.h).
  double jump_margin = 2.0;
  bool hold_on_leaving = true;  ///< hold at once when the verdict is kLeaving
  bool hold_on_faults = true;   ///< hold when a fault outlasts its time above
};

/// \brief One tick's status (file comment). Plain data: copying it allocates nothing.
struct ExecutionStatus {
  double plan_time = 0.0;           ///< t of the tick [s]
  double position_deviation = 0.0;  ///< |part position - reference| [m]
  double angle_deviation = 0.0;     ///< |part angle - reference| [deg]
  double stroke_deviation = 0.0;    ///< largest relied-on |stroke - reference| [m]
  /// \brief Largest relied-on |stroke rate - reference| in the estimate [m/s]: a finger
  ///        that loses its load accelerates at its force over its mass.
  double stroke_speed_deviation = 0.0;
  ContactRoles planned{};          ///< the roles the law keeps (finger order)
  ContactModes estimated{};        ///< the estimate's touching, sticking, sliding
  std::uint32_t contact_open = 0;  ///< relied-on contacts open (bit i: finger i)
  std::uint32_t slider_stuck = 0;  ///< planned sliders not yet loose
  std::uint32_t tip_slipping = 0;  ///< planned sticking tips slipping
  bool saturated = false;          ///< an input at its limit this tick
  bool pose_seen = false;          ///< a part pose has arrived in this run
  double pose_age = 0.0;           ///< t - the newest pose's stamp [s] (when pose_seen)
  std::uint64_t bad_readings = 0;  ///< non-finite joint readings, poses and times so far
  std::uint32_t flags = 0;         ///< ExecutionFlag bits of this tick
  ExecutionVerdict verdict = ExecutionVerdict::kOnPlan;
  HoldReason hold_reason = HoldReason::kNone;
  double hold_time = 0.0;  ///< plan time the hold began [s] (when holding)
};

}  // namespace rbsf
