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

/// \brief One solve(): its clock, the timing its references use, the plan kept so far and why
///        the last attempt found nothing.
class SupportPlanner::Run {
 public:
  using Clock = std::chrono::steady_clock;

  Run(SupportPlanner& planner, const Problem& problem, plan::Plan& plan,
      const std::atomic<bool>* cancel)
      : p_(planner),
        s_(planner.settings_),
        problem_(problem),
        plan_(plan),
        cancel_(cancel),
        t0_(Clock::now()) {
    // The cell's motion limits bound the timing's speeds (the part turns with psi and theta).
    timing_ = s_.timing;
    const MotionLimits& limits = p_.model_.cell().motion_limits;
    timing_.part_speed = std::min(timing_.part_speed, limits.part_speed);
    timing_.angular_speed = std::min(timing_.angular_speed, 0.5 * limits.angular_speed);
  }

  bool solve() {
    searchSimpleTurns();
    searchGeneral();
    if (!have_) {
      p_.message_ = cancelled() ? "cancelled" : why_.empty() ? "no time left for a search" : why_;
      return false;
    }
    plan_.planner = "support";
    plan_.start = problem_.start;
    plan_.start_theta = problem_.start_theta;
    plan_.propagations = static_cast<std::uint64_t>(p_.expansions_);
    plan_.planning_time = std::chrono::duration<double>(Clock::now() - t0_).count();
    return true;
  }

 private:
  double timeLeft() const {
    return s_.time_limit - std::chrono::duration<double>(Clock::now() - t0_).count();
  }
  bool budgetLeft() const {
    return timeLeft() > 0.0 && (s_.max_expansions <= 0 || p_.expansions_ < s_.max_expansions);
  }
  bool cancelled() const { return cancel_ != nullptr && cancel_->load(); }
  /// The expansion cap of the next search: its own, within what the planner has left.
  long expansionCap(long own) const { return std::min(own, s_.max_expansions - p_.expansions_); }

  /// Simple turns first (pivot_turn_search.h): one pivot, the fewest runs a turn can have.
  void searchSimpleTurns() {
    for (double use : s_.simple_turn_friction_uses) {
      if (runs_ || cancelled() || !budgetLeft()) break;
      SupportSearchSettings ss = s_.search;
      ss.support.law = s_.feedback.forces;
      ss.support.balance.friction_use = use;
      SupportSearch search(p_.model_, ss);
      PivotTurnSearch simple(search, s_.simple_turn);
      for (int n = 0; n < std::max(1, s_.max_paths) && !runs_ && budgetLeft(); ++n) {
        simple.setTimeLimit(timeLeft());
        if (s_.max_expansions > 0)
          simple.setMaxExpansions(expansionCap(s_.simple_turn.max_expansions));
        const SupportPath path =
            simple.search(problem_.start, problem_.start_theta, problem_.goal, cancel_);
        p_.expansions_ += path.expansions;
        if (!path.found) {
          why_ = path.message;
          break;
        }
        if (!tryPath(path, search, use)) break;
      }
    }
  }

  /// The general search at each friction use in turn, until a run ends on the goal.
  void searchGeneral() {
    for (double use : s_.friction_uses) {
      if (runs_ || cancelled()) break;
      SupportSearchSettings ss = s_.search;
      ss.support.law = s_.feedback.forces;
      ss.support.balance.friction_use = use;
      SupportSearch search(p_.model_, ss);
      for (int n = 0; n < std::max(1, s_.max_paths) && !runs_ && budgetLeft(); ++n) {
        search.setTimeLimit(timeLeft());
        if (s_.max_expansions > 0) search.setMaxExpansions(expansionCap(ss.max_expansions));
        const SupportPath path =
            search.search(problem_.start, problem_.start_theta, problem_.goal, cancel_);
        p_.expansions_ += path.expansions;
        p_.reach_.merge(path.reach);
        if (!path.found) {
          why_ = path.message;
          break;
        }
        if (!tryPath(path, search, use)) break;
      }
    }
  }

  /// Runs `path` closed loop and keeps its plan when the run ends on the goal or follows its
  /// reference longer than the plan kept. When the run misses the goal, the stretch where it
  /// departed is blocked in `search`; false when nothing new was blocked (the same path
  /// would come again).
  bool tryPath(const SupportPath& path, SupportSearch& search, double use) {
    ++p_.paths_;
    std::vector<SupportRun> stretches;
    ReferenceTrajectory reference;
    try {
      reference = supportReference(p_.model_, search.geometry(), path, timing_, &stretches);
    } catch (const SupportReferenceError& e) {
      for (std::size_t k = e.first_step; k <= e.last_step; ++k)
        search.block(path.steps[k], s_.block_radius);
      why_ = e.what();
      return true;
    }
    plan::Plan run =
        closedLoopPlan(p_.model_, reference, s_.simulator, s_.feedback, problem_.goal,
                       problem_.tolerance.position, problem_.tolerance.angle, s_.sample_steps);
    runs_ = run.status == plan::PlanStatus::kExact;
    // Where the run left its reference: the stretch to blame (the end when it never did).
    const double departs = departureTime(run, reference, s_.departure_position, s_.departure_angle);
    const double lasted = departs < 0.0 ? reference.endTime() : departs;
    if (runs_ || !have_ || lasted > followed_) {
      plan_ = std::move(run);
      followed_ = lasted;
      p_.friction_use_ = use;
      have_ = true;
    }
    if (runs_) return true;
    why_ = "no support path found has a closed-loop run that ends on the goal";
    const std::size_t blocked = search.blockedCount();
    for (const SupportRun& s : stretches)
      if (lasted >= s.start && lasted <= s.end)
        for (std::size_t k = s.first_step; k <= s.last_step; ++k)
          search.block(path.steps[k], s_.block_radius);
    return search.blockedCount() != blocked;
  }

  SupportPlanner& p_;
  const SupportPlannerSettings& s_;
  const Problem& problem_;
  plan::Plan& plan_;
  const std::atomic<bool>* cancel_;
  const Clock::time_point t0_;
  SupportTiming timing_;
  bool have_ = false;       // plan_ holds a run
  bool runs_ = false;       // plan_'s run ends on the goal
  double followed_ = -1.0;  // how long plan_'s run followed its reference [s]
  std::string why_;
};

bool SupportPlanner::solve(const Problem& problem, plan::Plan& plan,
                           const std::atomic<bool>* cancel) {
  message_.clear();
  expansions_ = 0;
  friction_use_ = 0.0;
  paths_ = 0;
  reach_ = SupportReach{};
  plan = plan::Plan{};
  return Run(*this, problem, plan, cancel).solve();
}

plan::PlanMargins SupportPlanner::margins() const {
  plan::PlanMargins m;
  m.support = true;
  m.friction_use = friction_use_;
  m.normal_margin = settings_.search.support.balance.normal_margin;
  return m;
}

}  // namespace rbsf::planner
