#pragma once
/// \file
/// \brief How fast a plan may move the part (cell file section `motion_limits`): a heavy
///        part is handled, not thrown. Part of a Cell (cell.h).
///
/// ```yaml
/// motion_limits:
///   part_speed: 0.25       # |(x', y')| of the part's COM at every plan sample [m/s]
///   angular_speed: 1.0     # |phi'| at every plan sample [rad/s]
///   rest: [0.001, 0.001]   # at rest: at most [m/s, rad/s], for the plan's last sample and
///                          # for a trial's mean speeds over its last second (trial.h)
/// ```
///
/// Every key is optional, with the defaults above. A plan outside these limits is not
/// certified, whatever its trials (plan_motion.h, certificate.h); a trial that does not end
/// at this rest fails.

namespace rbsf {

/// \brief The speeds a plan may reach and the rest it must end in (file comment).
struct MotionLimits {
  double part_speed = 0.25;          ///< [m/s]
  double angular_speed = 1.0;        ///< [rad/s]
  double rest_speed = 1e-3;          ///< [m/s]
  double rest_angular_speed = 1e-3;  ///< [rad/s]
};

}  // namespace rbsf
