#pragma once
/// \file
/// \brief Whether a plan handles the part within the cell's motion limits
///        (motion_limits.h): the peak part speed |(x', y')| and angular speed |phi'| over
///        the plan's samples (plan.h: every sample_steps steps and at each segment end),
///        and whether its last sample is at rest.

#include <string>

#include "rbsf/dynamics/core/motion_limits.h"

namespace rbsf::plan {

struct Plan;

/// \brief The plan's speeds against the limits (plan file key certificate.motion).
struct PlanMotion {
  bool measured = false;            ///< false: no samples (or a plan file without the key)
  double peak_speed = 0.0;          ///< max over samples of |(x', y')| [m/s]
  double peak_speed_time = 0.0;     ///< where [s]
  double peak_angular_speed = 0.0;  ///< max over samples of |phi'| [rad/s]
  double peak_angular_time = 0.0;   ///< where [s]
  double end_speed = 0.0;           ///< at the last sample [m/s]
  double end_angular_speed = 0.0;   ///< at the last sample [rad/s]
  MotionLimits limits;              ///< what it was judged against

  /// \brief Every sample within the speed limits.
  bool withinLimits() const {
    return peak_speed <= limits.part_speed && peak_angular_speed <= limits.angular_speed;
  }
  /// \brief The last sample at rest.
  bool endsAtRest() const {
    return end_speed <= limits.rest_speed && end_angular_speed <= limits.rest_angular_speed;
  }
  /// \brief Measured, within the limits and ending at rest.
  bool ok() const { return measured && withinLimits() && endsAtRest(); }
};

/// \brief The motion of `plan` judged against `limits`; not measured when the plan has no
///        samples.
PlanMotion measureMotion(const Plan& plan, const MotionLimits& limits);

/// \brief What breaks the limits, in metres and degrees ("moves the part at 1.47 m/s at
///        t = 2.3 s (limit 0.25 m/s); ends turning at 46 deg/s (rest: 0.057 deg/s)"),
///        empty when ok(); "the plan has no samples" when not measured.
std::string motionViolationText(const PlanMotion& motion);

/// \brief One line for reports: "motion: peak 0.081 m/s and 20 deg/s (limits 0.25 m/s,
///        57.3 deg/s), ends at rest" (or the violation).
std::string motionText(const PlanMotion& motion);

}  // namespace rbsf::plan
