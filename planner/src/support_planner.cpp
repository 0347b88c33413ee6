#include "rbsf/planner/support_planner.h"

#include <algorithm>
#include <chrono>
#include <memory>

namespace rbsf::planner {

SupportSearchSettings SupportPlannerSettings::defaultSearch() {
  SupportSearchSettings s;
  s.angle_step = 5.0 * M_PI / 180;
  s.xy_step = 0.02;
  s.heuristic_weight = 5.0;
  s.support.min_normal_cosine = 0.1;
  return s;
}

SupportPlanner::SupportPlanner(const RbsfModel& model, SupportPlannerSettings settings)
    : model_(model), settings_(std::move(settings)) {}

bool SupportPlanner::solve(const Problem& problem, plan::Plan& plan) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  message_.clear();
  expansions_ = 0;
  friction_use_ = 0.0;
  SupportPath path;
  std::unique_ptr<SupportSearch> search;
  for (double use : settings_.friction_uses) {
    SupportSearchSettings ss = settings_.search;
    ss.support.balance.friction_use = use;
    ss.time_limit = settings_.time_limit - std::chrono::duration<double>(Clock::now() - t0).count();
    if (ss.time_limit <= 0.0) break;
    search = std::make_unique<SupportSearch>(model_, ss);
    path = search->search(problem.start, problem.start_theta, problem.goal, settings_.cancel);
    expansions_ += path.expansions;
    if (path.found) {
      friction_use_ = use;
      break;
    }
    if (settings_.cancel != nullptr && settings_.cancel->load()) break;
  }
  if (!path.found) {
    message_ = path.message.empty() ? "no time left for a search" : path.message;
    plan = plan::Plan{};
    return false;
  }
  // The cell's motion limits bound the timing's speeds (the part turns with psi and theta).
  SupportTiming timing = settings_.timing;
  const MotionLimits& limits = model_.cell().motion_limits;
  timing.part_speed = std::min(timing.part_speed, limits.part_speed);
  timing.angular_speed = std::min(timing.angular_speed, 0.5 * limits.angular_speed);
  const ReferenceTrajectory reference = supportReference(model_, search->geometry(), path, timing);
  plan = closedLoopPlan(model_, reference, settings_.simulator, settings_.feedback, problem.goal,
                        settings_.position_tolerance, settings_.angle_tolerance,
                        settings_.sample_steps);
  plan.planner = "support";
  plan.start = problem.start;
  plan.start_theta = problem.start_theta;
  plan.propagations = static_cast<std::uint64_t>(expansions_);
  plan.planning_time = std::chrono::duration<double>(Clock::now() - t0).count();
  return true;
}

}  // namespace rbsf::planner
