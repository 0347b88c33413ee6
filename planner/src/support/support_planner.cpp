#include "rbsf/planner/support/support_planner.h"

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
  // Runs `path` closed loop and keeps its plan when the run ends on the goal or follows its
  // reference longer than the plan kept. When the run misses the goal, the stretch where it
  // departed is blocked in `search`; false when nothing new was blocked (the same path
  // would come again).
  auto tryPath = [&](const SupportPath& path, SupportSearch& search, double use) {
    ++paths_;
    std::vector<SupportRun> stretches;
    ReferenceTrajectory reference;
    try {
      reference = supportReference(model_, search.geometry(), path, timing, &stretches);
    } catch (const SupportReferenceError& e) {
      for (std::size_t k = e.first_step; k <= e.last_step; ++k)
        search.block(path.steps[k], settings_.block_radius);
      why = e.what();
      return true;
    }
    plan::Plan run =
        closedLoopPlan(model_, reference, settings_.simulator, settings_.feedback, problem.goal,
                       problem.tolerance.position, problem.tolerance.angle, settings_.sample_steps);
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
    if (runs) return true;
    why = "no support path found has a closed-loop run that ends on the goal";
    const std::size_t blocked = search.blockedCount();
    for (const SupportRun& s : stretches)
      if (lasted >= s.start && lasted <= s.end)
        for (std::size_t k = s.first_step; k <= s.last_step; ++k)
          search.block(path.steps[k], settings_.block_radius);
    return search.blockedCount() != blocked;
  };
  auto budgetLeft = [&] {
    return timeLeft() > 0.0 &&
           (settings_.max_expansions <= 0 || expansions_ < settings_.max_expansions);
  };
  auto cancelled = [&] { return settings_.cancel != nullptr && settings_.cancel->load(); };

  // Simple turns first (pivot_turn_search.h): one pivot, the fewest runs a turn can have.
  for (double use : settings_.simple_turn_friction_uses) {
    if (runs || cancelled() || !budgetLeft()) break;
    SupportSearchSettings ss = settings_.search;
    ss.support.balance.friction_use = use;
    SupportSearch search(model_, ss);
    PivotTurnSearch simple(search, settings_.simple_turn);
    for (int n = 0; n < std::max(1, settings_.max_paths) && !runs && budgetLeft(); ++n) {
      simple.setTimeLimit(timeLeft());
      if (settings_.max_expansions > 0)
        simple.setMaxExpansions(
            std::min(settings_.simple_turn.max_expansions, settings_.max_expansions - expansions_));
      const SupportPath path =
          simple.search(problem.start, problem.start_theta, problem.goal, settings_.cancel);
      expansions_ += path.expansions;
      if (!path.found) {
        why = path.message;
        break;
      }
      if (!tryPath(path, search, use)) break;
    }
  }
  for (double use : settings_.friction_uses) {
    if (runs || cancelled()) break;
    SupportSearchSettings ss = settings_.search;
    ss.support.balance.friction_use = use;
    SupportSearch search(model_, ss);
    for (int n = 0; n < std::max(1, settings_.max_paths) && !runs && budgetLeft(); ++n) {
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
      if (!tryPath(path, search, use)) break;
    }
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

plan::PlanMargins SupportPlanner::margins() const {
  plan::PlanMargins m;
  m.support = true;
  m.friction_use = friction_use_;
  m.normal_margin = settings_.search.support.balance.normal_margin;
  return m;
}

}  // namespace rbsf::planner
