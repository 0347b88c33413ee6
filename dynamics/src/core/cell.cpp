/// \file
/// \brief Cell validation (cell.h): the rules every cell is held to, from a file
///        (io/cell_file.h) or built in code, with messages naming the key.

#include "rbsf/dynamics/core/cell.h"

#include <cmath>
#include <set>
#include <string_view>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/input_checks.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

void Cell::validate() const {
  const InputChecker c{messagePrefix(name)};
  c.nonNegative(gravity, "gravity");
  c.nonNegative(base.inertia, "base.inertia");
  c.interval(base.theta_min, base.theta_max, "base.theta_limits");
  // Angles in cell files are radians; a limit beyond half a turn is almost surely degrees.
  if (std::abs(base.theta_min) > M_PI + 1e-3 || std::abs(base.theta_max) > M_PI + 1e-3)
    c.fail("base.theta_limits must lie within [-pi, pi] radians (got [" +
           roundTripText(base.theta_min) + ", " + roundTripText(base.theta_max) + "])");
  c.positive(base.torque_limit, "base.torque_limit");
  if (fingers.empty()) c.fail("fingers must list at least one finger");
  if (numFingers() > kMaxFingers)
    c.fail("fingers lists " + std::to_string(numFingers()) + " fingers; at most " +
           std::to_string(kMaxFingers) + " are supported");
  for (int i = 0; i < numFingers(); ++i) {
    const FingerParams& f = fingers[i];
    const std::string p = "fingers[" + std::to_string(i) + "].";
    c.finite(f.r, p + "r");
    c.interval(f.stroke_min, f.stroke_max, p + "stroke");
    c.positive(f.mass, p + "mass");
    c.positive(f.force_limit, p + "force_limit");
    c.finite(f.com_offset, p + "com_offset");
    c.nonNegative(f.inertia, p + "inertia");
  }
  if (!object.shape) c.fail("object.shape is missing");
  // A body's COM lies inside its convex hull: the origin must be left of every tangent
  // line (by more than 1 nm, so a COM on the boundary is rejected too).
  for (int k = 0; k < 256; ++k) {
    Vec2 p, dp, ddp;
    object.shape->derivatives(2 * M_PI * k / 256, p, dp, ddp);
    if (!(cross(p, dp) > 1e-9 * dp.norm()))
      c.fail("object.shape.center puts the COM (the object-frame origin) outside the shape");
  }
  c.positive(object.mass, "object.mass");
  c.positive(object.inertia, "object.inertia");
  c.nonNegative(friction.mu_static, "friction.static");
  c.nonNegative(friction.mu_kinetic, "friction.kinetic");
  if (friction.mu_kinetic > friction.mu_static)
    c.fail("friction.kinetic (" + roundTripText(friction.mu_kinetic) +
           ") must not exceed friction.static (" + roundTripText(friction.mu_static) + ")");

  // sensing (sensing.h). part_pose is checked even when absent (`none`): its defaults pass.
  c.nonNegative(sensing.joints.angle_noise, "sensing.joints.noise[0]");
  c.nonNegative(sensing.joints.stroke_noise, "sensing.joints.noise[1]");
  const PartPoseSensing& pp = sensing.part_pose;
  c.positive(pp.rate, "sensing.part_pose.rate");
  c.atMost(pp.rate, 10000.0, "10000 Hz", "sensing.part_pose.rate");
  c.nonNegative(pp.latency, "sensing.part_pose.latency");
  c.atMost(pp.latency, 1.0, "1 s", "sensing.part_pose.latency");
  c.nonNegative(pp.position_noise, "sensing.part_pose.noise[0]");
  c.nonNegative(pp.angle_noise, "sensing.part_pose.noise[1]");

  c.positive(motion_limits.part_speed, "motion_limits.part_speed");
  c.positive(motion_limits.angular_speed, "motion_limits.angular_speed");
  c.positive(motion_limits.rest_speed, "motion_limits.rest[0]");
  c.positive(motion_limits.rest_angular_speed, "motion_limits.rest[1]");

  // uncertainty: a draw must keep masses, inertias, friction and gains positive.
  const Uncertainty& u = uncertainty;
  c.fraction(u.mass, "uncertainty.mass");
  c.fraction(u.inertia, "uncertainty.inertia");
  c.fraction(u.static_friction, "uncertainty.static_friction");
  c.fraction(u.actuator_gain, "uncertainty.actuator_gain");
  c.nonNegative(u.com, "uncertainty.com");
  c.atMost(u.com, 0.1, "0.1 m", "uncertainty.com");
  c.nonNegative(u.initial_position, "uncertainty.initial_position");
  c.atMost(u.initial_position, 0.1, "0.1 m", "uncertainty.initial_position");
  c.nonNegative(u.initial_angle, "uncertainty.initial_angle");
  c.atMost(u.initial_angle, M_PI / 4, "pi/4 rad", "uncertainty.initial_angle");
  c.nonNegative(u.kinetic_friction_min, "uncertainty.kinetic_friction[0]");
  c.finite(u.kinetic_friction_max, "uncertainty.kinetic_friction[1]");
  if (!(u.kinetic_friction_min <= u.kinetic_friction_max))
    c.fail("uncertainty.kinetic_friction must be [min, max] with min <= max (got [" +
           roundTripText(u.kinetic_friction_min) + ", " + roundTripText(u.kinetic_friction_max) +
           "])");

  // faults (faults.h): rates and shares of a sensible run.
  const Faults& f = faults;
  c.nonNegative(f.pose_dropouts.rate, "faults.pose_dropouts.rate");
  c.atMost(f.pose_dropouts.rate, 100.0, "100 per s", "faults.pose_dropouts.rate");
  c.positive(f.pose_dropouts.length, "faults.pose_dropouts.length");
  c.atMost(f.pose_dropouts.length, 10.0, "10 s", "faults.pose_dropouts.length");
  c.nonNegative(f.joint_spikes.rate, "faults.joint_spikes.rate");
  c.atMost(f.joint_spikes.rate, 1000.0, "1000 per s", "faults.joint_spikes.rate");
  c.nonNegative(f.joint_spikes.size, "faults.joint_spikes.size");
  c.atMost(f.joint_spikes.size, 1.0, "1 rad or m", "faults.joint_spikes.size");
  c.nonNegative(f.joint_spikes.nan_share, "faults.joint_spikes.nan");
  c.atMost(f.joint_spikes.nan_share, 1.0, "1", "faults.joint_spikes.nan");
  c.nonNegative(f.missed_tick_rate, "faults.missed_ticks.rate");
  c.atMost(f.missed_tick_rate, 1000.0, "1000 per s", "faults.missed_ticks.rate");
  c.nonNegative(f.force_cut_chance, "faults.force_cut.chance");
  c.atMost(f.force_cut_chance, 1.0, "1", "faults.force_cut.chance");
  c.nonNegative(f.force_cut_to, "faults.force_cut.to");
  c.atMost(f.force_cut_to, 1.0, "1", "faults.force_cut.to");
  c.fraction(f.mass_error, "faults.mass_error");
}

double Cell::inputLimit(int j) const {
  return j == layout::kTauTheta ? base.torque_limit : fingers[j - 1].force_limit;
}

}  // namespace rbsf
