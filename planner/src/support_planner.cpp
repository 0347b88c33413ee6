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
  auto timeLeft = [&] {
    return settings_.time_limit - std::chrono::duration<double>(Clock::now() - t0).count();
  };
  message_.clear();
  expansions_ = 0;
  friction_use_ = 0.0;
  paths_ = 0;
  reach_ = SupportReach{};
  plan = plan::Plan{};
  // The cell's motion limits bound the timing's speeds (the part turns with psi and theta).
  SupportTiming timing = settings_.timing;
  const MotionLimits& limits = model_.cell().motion_limits;
  timing.part_speed = std::min(timing.part_speed, limits.part_speed);
  timing.angular_speed = std::min(timing.angular_speed, 0.5 * limits.angular_speed);

  bool have = false, runs = false;
  double followed = -1.0;  // how long `plan`'s run followed its reference [s]
  std::string why;
  for (double use : settings_.friction_uses) {
    SupportSearchSettings ss = settings_.search;
    ss.support.balance.friction_use = use;
    SupportSearch search(model_, ss);
    for (int n = 0; n < std::max(1, settings_.max_paths) && !runs; ++n) {
      if (timeLeft() <= 0.0) break;
      if (settings_.max_expansions > 0 && expansions_ >= settings_.max_expansions) break;
      search.setTimeLimit(timeLeft());
      if (settings_.max_expansions > 0)
        search.setMaxExpansions(
            std::min(ss.max_expansions, settings_.max_expansions - expansions_));
      const SupportPath path =
          search.search(problem.start, problem.start_theta, problem.goal, settings_.cancel);
      expansions_ += path.expansions;
      reach_.merge(path.reach);
      if (!path.found) {
        why = path.message;
        break;
      }
      ++paths_;
      std::vector<SupportRun> stretches;
      ReferenceTrajectory reference;
      try {
        reference = supportReference(model_, search.geometry(), path, timing, &stretches);
      } catch (const SupportReferenceError& e) {
        for (std::size_t k = e.first_step; k <= e.last_step; ++k)
          search.block(path.steps[k], settings_.block_radius);
        why = e.what();
        continue;
      }
      plan::Plan run = closedLoopPlan(model_, reference, settings_.simulator, settings_.feedback,
                                      problem.goal, settings_.position_tolerance,
                                      settings_.angle_tolerance, settings_.sample_steps);
      runs = run.status == plan::PlanStatus::kExact;
      // Where the run left its reference: the stretch to blame (the end when it never did).
      const double departs =
          departureTime(run, reference, settings_.departure_position, settings_.departure_angle);
      const double lasted = departs < 0.0 ? reference.endTime() : departs;
      if (runs || !have || lasted > followed) {
        plan = std::move(run);
        followed = lasted;
        friction_use_ = use;
        have = true;
      }
      if (runs) break;
      why = "no support path found has a closed-loop run that ends on the goal";
      const std::size_t blocked = search.blockedCount();
      for (const SupportRun& s : stretches)
        if (lasted >= s.start && lasted <= s.end)
          for (std::size_t k = s.first_step; k <= s.last_step; ++k)
            search.block(path.steps[k], settings_.block_radius);
      if (search.blockedCount() == blocked) break;  // the same path would come again
    }
    if (runs || (settings_.cancel != nullptr && settings_.cancel->load())) break;
  }
  if (!have) {
    message_ = why.empty() ? "no time left for a search" : why;
    return false;
  }
  plan.planner = "support";
  plan.start = problem.start;
  plan.start_theta = problem.start_theta;
  plan.propagations = static_cast<std::uint64_t>(expansions_);
  plan.planning_time = std::chrono::duration<double>(Clock::now() - t0).count();
  return true;
}

}  // namespace rbsf::planner
