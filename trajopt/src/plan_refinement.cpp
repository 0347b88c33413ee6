#include "rbsf/trajopt/plan_refinement.h"

#include <cmath>
#include <exception>
#include <sstream>

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

/// One solve and its verdict.
struct Attempt {
  OptimizedPlan opt;
  planner::OptimizationSummary summary;
  planner::ReplaySummary verdict;
  std::string reason;  ///< empty when accepted
  std::string note;    ///< non-finite summary numbers, zeroed
  bool accepted = false;

  /// \brief The summary's message: `text`, then the note.
  void setMessage(const std::string& text) {
    summary.message = text;
    if (!note.empty()) summary.message += (text.empty() ? "" : "; ") + note;
  }
};

Attempt attempt(const PlanOptimizer& optimizer, const Simulator& simulator,
                const planner::Plan& plan, const planner::ReplaySettings& replay) {
  Attempt a;
  a.opt = optimizer.optimize(plan);
  a.summary = a.opt.plan.optimization;
  a.summary.ran = true;
  finite(a.summary.solve_time, "solve_time", a.note);
  finite(a.summary.cost_before, "cost_before", a.note);
  finite(a.summary.cost_after, "cost_after", a.note);
  if (!a.opt.success) {
    a.reason = "optimisation failed (Ipopt status " + a.summary.status + ")";
    if (!a.summary.message.empty()) a.reason += ": " + a.summary.message;
  } else {
    std::string why = "it holds a non-finite value";
    if (finitePlan(a.opt.plan)) {
      try {
        a.verdict = planner::verifyPlan(simulator, a.opt.plan, replay, &why);
      } catch (const std::exception& e) {  // e.g. a bad knot: not the user's input
        a.verdict = {};
        why = std::string("cannot replay it: ") + e.what();
      }
    }
    if (!a.verdict.ran) {
      a.reason = "optimised plan rejected: " + why;
    } else if (!finiteReplay(a.verdict.closed_loop) || !finiteReplay(a.verdict.open_loop)) {
      a.verdict = {};  // a diverged replay is not written
      a.reason = "optimised plan rejected: its replay diverged (non-finite state)";
    } else if (!a.verdict.accepted) {
      a.reason = "optimised plan rejected: " + why;
    }
  }
  a.accepted = a.opt.success && a.verdict.accepted;
  a.setMessage(a.reason);
  return a;
}

}  // namespace

RefineOutcome refinePlan(const PlanOptimizer& optimizer, const Simulator& simulator,
                         const planner::Plan& plan, const planner::ReplaySettings& replay,
                         const RefineSettings& settings) {
  RefineOutcome out;
  Attempt first = attempt(optimizer, simulator, plan, replay);
  out.attempts = 1;
  const OptimizerSettings& os = optimizer.settings();
  const bool cancelled = os.cancel != nullptr && os.cancel->load();
  const double retry = settings.retry_min_slip_rate;
  Attempt* chosen = &first;
  Attempt second;
  if (!first.accepted && !cancelled && retry > 0.0 && retry != os.min_slip_rate) {
    OptimizerSettings again = os;
    again.min_slip_rate = retry;
    second = attempt(PlanOptimizer(optimizer.model(), again), simulator, plan, replay);
    out.attempts = 2;
    std::ostringstream what;
    what << "retry with min_slip_rate = " << retry;
    if (second.accepted) {
      chosen = &second;
      second.setMessage(what.str() + " accepted; the first solve's " + first.reason);
    } else {
      first.reason += "; " + what.str() + ": " + second.reason;
      first.setMessage(first.reason);
    }
  }
  out.accepted = chosen->accepted;
  out.reason = chosen->reason;
  out.plan = out.accepted ? std::move(chosen->opt.plan) : plan;
  out.plan.optimization = chosen->summary;
  out.plan.replay = chosen->verdict;
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
