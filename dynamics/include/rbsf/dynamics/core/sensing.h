#pragma once
/// \file
/// \brief What a cell measures (cell file section `sensing`), and the uncertainty a plan
///        must tolerate (section `uncertainty`). Both are part of a Cell (cell.h).
///
/// ```yaml
/// sensing:
///   joints: {noise: [1.0e-5, 1.0e-6]}           # [rad, m], 1 sigma, every control step
///   part_pose: {rate: 100, latency: 0.01, noise: [0.0005, 0.005236]}   # [Hz, s, m, rad]
///   # or: part_pose: none                       # the cell sees only its joints
/// uncertainty:
///   mass: 0.05          # part mass +- 5 % (relative)
///   inertia: 0.10       # part inertia +- 10 % (relative)
///   com: 0.002          # COM +- 2 mm in x and y of the part frame [m]
///   static_friction: 0.20      # mu_s +- 20 % (relative)
///   kinetic_friction: [0.0, 0.05]   # mu_k drawn in this range when the cell says 0
///   initial_position: 0.001    # start pose +- 1 mm in x and y [m]
///   initial_angle: 0.008727    # and +- 0.5 deg [rad]
///   actuator_gain: 0.02        # each input scaled by 1 +- 2 %
/// ```
///
/// Defaults (a section or key left out): a part-pose sensor over the jig (a camera or a
/// laser tracker) at 100 Hz with 10 ms latency and 0.5 mm / 0.3 deg noise; joint encoders
/// with 1e-5 rad / 1e-6 m noise; the uncertainty above. Noise is Gaussian with the given
/// standard deviation, independent per coordinate and sample. Every +- range is drawn
/// uniformly (certificate.h).

#include <cmath>

namespace rbsf {

/// \brief Joint encoders: theta and every stroke, sampled every control step.
struct JointSensing {
  double angle_noise = 1e-5;   ///< 1 sigma on theta [rad]
  double stroke_noise = 1e-6;  ///< 1 sigma on each l_i [m]
};

/// \brief A sensor of the part's pose (x, y, phi) over the jig.
struct PartPoseSensing {
  bool present = true;                      ///< false: `part_pose: none`
  double rate = 100.0;                      ///< samples per second [Hz]
  double latency = 0.01;                    ///< a sample describes the part this long ago [s]
  double position_noise = 5e-4;             ///< 1 sigma on x and y [m]
  double angle_noise = 0.3 * M_PI / 180.0;  ///< 1 sigma on phi [rad]
};

/// \brief Everything the cell measures.
struct Sensing {
  JointSensing joints;
  PartPoseSensing part_pose;
};

/// \brief Half-widths of the uniform draws of one certificate trial.
struct Uncertainty {
  double mass = 0.05;                         ///< relative, part mass
  double inertia = 0.10;                      ///< relative, part inertia about its COM
  double com = 0.002;                         ///< COM offset in x and y of the part frame [m]
  double static_friction = 0.20;              ///< relative, mu_s
  double kinetic_friction_min = 0.0;          ///< mu_k drawn in [min, max] when the cell's is 0
  double kinetic_friction_max = 0.05;         ///< (otherwise mu_k scales with mu_s)
  double initial_position = 0.001;            ///< start COM x and y [m]
  double initial_angle = 0.5 * M_PI / 180.0;  ///< start angle [rad]
  double actuator_gain = 0.02;                ///< relative, each input
};

}  // namespace rbsf
