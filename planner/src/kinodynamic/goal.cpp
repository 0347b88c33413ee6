#include "rbsf/planner/kinodynamic/goal.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {

double goalAngleError(double phi, double phi_goal, bool absolute_angle) {
  return absolute_angle ? phi - phi_goal : angleDifference(phi, phi_goal);
}

PoseGoal::PoseGoal(const ompl::base::SpaceInformationPtr& si, const Pose& goal,
                   double position_tolerance, double angle_tolerance,
                   const SupportValidityChecker& support, bool absolute_angle)
    : ompl::base::GoalRegion(si),
      goal_(goal),
      position_tolerance_(position_tolerance),
      angle_tolerance_(angle_tolerance),
      support_(support),
      absolute_angle_(absolute_angle) {
  setThreshold(1.0);
}

double PoseGoal::distanceGoal(const ompl::base::State* state) const {
  const double* x = state->as<SimStateSpace::StateType>()->values;
  const double dp = std::hypot(x[layout::kX] - goal_.x, x[layout::kY] - goal_.y);
  const double da = std::abs(goalAngleError(x[layout::kPhi], goal_.phi, absolute_angle_));
  return std::max(dp / position_tolerance_, da / angle_tolerance_);
}

bool PoseGoal::isSatisfied(const ompl::base::State* state, double* distance) const {
  const double d = distanceGoal(state);
  if (distance) *distance = d;
  const auto* s = state->as<SimStateSpace::StateType>();
  const bool ok = d <= threshold_ && support_.supported(s->sim->q, s->sim->xi_hint);
  if (ok || d < best_) best_ = std::min(best_, d);
  reached_ = reached_ || ok;
  return ok;
}

}  // namespace rbsf::planner
