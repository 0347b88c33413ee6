#pragma once
/// \file
/// \brief The placement rule: finger strokes that put every tip on the object's underside.

#include <string>

#include "rbsf/dynamics/core/model.h"

namespace rbsf {

/// \brief Object pose: COM (x, y) [m] in the world frame and angle phi [rad].
struct Pose {
  double x = 0.0;
  double y = 0.0;
  double phi = 0.0;
};

/// \brief Result of placeFingers().
struct Placement {
  bool ok = false;
  VecC strokes;         ///< l_i [m] for every finger, when ok
  int finger = -1;      ///< first finger that cannot reach (0-based), when not ok
  std::string message;  ///< why finger `finger` cannot reach, when not ok
};

/// \brief For each finger i, the stroke l_i at which the tip, moving along the base y
///        axis from R(theta) (r_i, 0), first meets the object's boundary from below
///        (the entry point of the line into the convex part). Fails for the first finger
///        whose line misses the part or whose stroke would leave [stroke_min, stroke_max].
Placement placeFingers(const RbsfModel& model, const Pose& pose, double theta);

/// \brief q = (pose, theta, strokes of placeFingers()).
/// \throws InputError with placeFingers()'s message when a finger cannot reach.
VecQ restingConfiguration(const RbsfModel& model, const Pose& pose, double theta);

/// \brief a - b wrapped to (-pi, pi] [rad]: the turn from b to a the shorter way.
double angleDifference(double a, double b);

}  // namespace rbsf
