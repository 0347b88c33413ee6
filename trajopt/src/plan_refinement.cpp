#include "rbsf/trajopt/plan_refinement.h"

#include <cmath>
#include <exception>

namespace rbsf::trajopt {

namespace {

/// Zero a non-finite number, noting it in `note`.
void finite(double& x, const char* what, std::string& note) {
  if (std::isfinite(x)) return;
  x = 0.0;
  note += std::string(note.empty() ? "" : "; ") + what + " not finite (written as 0)";
}

bool finiteReplay(const planner::ReplayResult& r) {
  return std::isfinite(r.position_error) && std::isfinite(r.angle_error) &&
         std::isfinite(r.min_f_n) && std::isfinite(r.max_tracking_error);
}

/// Every number the plan file would hold for the segments and samples is finite.
bool finitePlan(const planner::Plan& p) {
  for (const planner::PlanSegment& s : p.segments)
    if (!std::isfinite(s.duration) || !s.tau.allFinite() || !s.tau_end.allFinite()) return false;
  for (const planner::PlanSample& s : p.samples)
    if (!std::isfinite(s.t) || !s.q.allFinite() || !s.v.allFinite() || !s.tau.allFinite() ||
        !s.f_n.allFinite())
      return false;
  return true;
}

}  // namespace

RefineOutcome refinePlan(const PlanOptimizer& optimizer, const Simulator& simulator,
                         const planner::Plan& plan, const planner::ReplaySettings& replay) {
  RefineOutcome out;
  OptimizedPlan opt = optimizer.optimize(plan);
  planner::OptimizationSummary summary = opt.plan.optimization;
  summary.ran = true;
  std::string note;
  finite(summary.solve_time, "solve_time", note);
  finite(summary.cost_before, "cost_before", note);
  finite(summary.cost_after, "cost_after", note);

  planner::ReplaySummary verdict;
  if (!opt.success) {
    out.reason = "optimisation failed (Ipopt status " + summary.status + ")";
    if (!summary.message.empty()) out.reason += ": " + summary.message;
  } else {
    std::string why = "it holds a non-finite value";
    if (finitePlan(opt.plan)) {
      try {
        verdict = planner::verifyPlan(simulator, opt.plan, replay, &why);
      } catch (const std::exception& e) {  // e.g. a bad knot: not the user's input
        verdict = {};
        why = std::string("cannot replay it: ") + e.what();
      }
    }
    if (!verdict.ran) {
      out.reason = "optimised plan rejected: " + why;
    } else if (!finiteReplay(verdict.closed_loop) || !finiteReplay(verdict.open_loop)) {
      verdict = {};  // a diverged replay is not written
      out.reason = "optimised plan rejected: its replay diverged (non-finite state)";
    } else if (!verdict.accepted) {
      out.reason = "optimised plan rejected: " + why;
    }
  }
  out.accepted = opt.success && verdict.accepted;
  out.plan = out.accepted ? std::move(opt.plan) : plan;
  if (!out.accepted) summary.message = out.reason;
  if (!note.empty()) summary.message += (summary.message.empty() ? "" : "; ") + note;
  out.plan.optimization = summary;
  out.plan.replay = verdict;
  if (!out.accepted) {
    // The plan in the file is the planner's: say whether it passes the same check, since a
    // planner's plan can be exact in simulation yet not survive joint tracking.
    try {
      out.plan.planner_replay = planner::verifyPlan(simulator, plan, replay);
    } catch (const std::exception&) {
      out.plan.planner_replay = {};
    }
    if (!finiteReplay(out.plan.planner_replay.closed_loop) ||
        !finiteReplay(out.plan.planner_replay.open_loop))
      out.plan.planner_replay = {};  // diverged: not written
  }
  return out;
}

}  // namespace rbsf::trajopt
