#pragma once
/// \file
/// \brief The goal: the part's pose within tolerances, the part supported.
///
/// distanceGoal = max(|(x, y) - (x_g, y_g)| / position_tolerance,
///                    |wrap(phi - phi_g)| / angle_tolerance)
/// (wrap to (-pi, pi]: a pose is reached whichever way the part turned), so the goal
/// region is distance <= 1. With absolute_angle the angle term is |phi - phi_g| unwrapped:
/// phi is the part's accumulated angle, so phi_g = -270 deg asks for a 270 degree turn. isSatisfied
/// also requires the part supported (validity.h). Every call of isSatisfied records the smallest
/// distance seen (progress and exit 3).

#include <limits>

#include <ompl/base/goals/GoalRegion.h>

#include "rbsf/dynamics/core/placement.h"
#include "rbsf/planner/kinodynamic/validity.h"

namespace rbsf::planner {

/// \brief Goal region over the object's pose.
class PoseGoal : public ompl::base::GoalRegion {
 public:
  PoseGoal(const ompl::base::SpaceInformationPtr& si, const Pose& goal, double position_tolerance,
           double angle_tolerance, const SupportValidityChecker& support,
           bool absolute_angle = false);

  double distanceGoal(const ompl::base::State* state) const override;
  bool isSatisfied(const ompl::base::State* state, double* distance) const override;
  using ompl::base::GoalRegion::isSatisfied;

  /// \brief Smallest distance (in tolerance units) passed to isSatisfied so far, supported
  ///        or not (the search's progress figure).
  double bestDistance() const { return best_; }
  /// \brief True once isSatisfied has accepted a state: within the region and supported.
  ///        (bestDistance() <= 1 alone may come from a part falling through the goal pose.)
  bool reached() const { return reached_; }
  /// \brief The goal pose, its tolerances ([m], [rad]) and whether its angle is a total turn.
  const Pose& pose() const { return goal_; }
  double positionTolerance() const { return position_tolerance_; }
  double angleTolerance() const { return angle_tolerance_; }
  bool absoluteAngle() const { return absolute_angle_; }

 private:
  Pose goal_;
  double position_tolerance_, angle_tolerance_;
  const SupportValidityChecker& support_;
  bool absolute_angle_;
  mutable double best_ = std::numeric_limits<double>::infinity();
  mutable bool reached_ = false;
};

/// \brief The goal's angle error phi - phi_g [rad]: wrapped to (-pi, pi], or plain when
///        `absolute_angle` (phi_g is a total turn).
double goalAngleError(double phi, double phi_goal, bool absolute_angle);

}  // namespace rbsf::planner
