#include "rbsf/trajopt/plan_refinement.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace rbsf::trajopt {

namespace {

/// Zero a non-finite number, noting it in `note`.
void finite(double& x, const char* what, std::string& note) {
  if (std::isfinite(x)) return;
  x = 0.0;
  note += std::string(note.empty() ? "" : "; ") + what + " not finite (written as 0)";
}

/// Every number the plan file would hold for the segments and samples is finite.
bool finitePlan(const plan::Plan& p) {
  for (const plan::PlanSegment& s : p.segments)
    if (!std::isfinite(s.duration) || !s.tau.allFinite() || !s.tau_end.allFinite()) return false;
  for (const plan::PlanSample& s : p.samples)
    if (!std::isfinite(s.t) || !s.q.allFinite() || !s.v.allFinite() || !s.tau.allFinite() ||
        !s.f_n.allFinite())
      return false;
  return true;
}

/// One solve: its plan when it succeeded and is finite, and its summary.
RefinementCandidate solve(const PlanOptimizer& optimizer, const plan::Plan& plan,
                          const std::atomic<bool>* cancel) {
  RefinementCandidate a;
  OptimizedPlan opt = optimizer.optimize(plan, cancel);
  a.summary = opt.summary;
  a.summary.ran = true;
  a.converged = opt.success;
  std::string note;
  finite(a.summary.solve_time, "solve_time", note);
  finite(a.summary.cost_before, "cost_before", note);
  finite(a.summary.cost_after, "cost_after", note);
  if (!opt.success) {
    a.reason =
        std::string("optimisation failed (Ipopt status ") + plan::toString(a.summary.status) + ")";
    if (!a.summary.message.empty()) a.reason += ": " + a.summary.message;
  } else if (!finitePlan(opt.plan)) {
    a.reason = "the optimised plan holds a non-finite value";
  } else {
    a.usable = true;
    a.plan = std::move(opt.plan);
  }
  if (!note.empty()) a.reason += (a.reason.empty() ? "" : "; ") + note;
  return a;
}

}  // namespace

OptimizerSettings supportOptimizerSettings(OptimizerSettings base, const plan::PlanMargins& margins,
                                           const SupportRefinement& support) {
  base.stated_roles = true;
  base.cone_margin = std::clamp(margins.friction_use, 1e-3, 1.0);
  base.normal_floor = std::max(margins.normal_margin, 0.0);
  base.keep_slide_direction = true;
  base.min_slip_rate = support.min_slip_rate;
  base.motion_limits = true;
  base.least_norm = true;
  base.keep_end_rest = true;
  base.tube_position = support.tube_position;
  base.tube_angle = support.tube_angle;
  base.duration_min_scale = support.duration_min_scale;
  return base;
}

PlanRefiner::PlanRefiner(const RbsfModel& model, OptimizerSettings settings, RefineSettings refine)
    : optimizer_(model, std::move(settings)), refine_(refine) {}

OptimizerSettings PlanRefiner::settingsFor(const plan::PlanMargins& margins, int k) const {
  OptimizerSettings s =
      margins.support ? supportOptimizerSettings(settings(), margins, refine_.support) : settings();
  // The retry changes the slip floor: to retry_min_slip_rate, or from it to none (a floor on
  // every interval of a slide can leave no path inside a support plan's tube).
  if (k > 0)
    s.min_slip_rate =
        s.min_slip_rate == refine_.retry_min_slip_rate ? 0.0 : refine_.retry_min_slip_rate;
  return s;
}

int PlanRefiner::candidates(const plan::PlanMargins& margins) const {
  const double first = settingsFor(margins, 0).min_slip_rate;
  const double retry = settingsFor(margins, 1).min_slip_rate;
  return refine_.retry_min_slip_rate > 0.0 && retry != first ? 2 : 1;
}

RefinementCandidate PlanRefiner::candidate(const plan::Plan& plan, const plan::PlanMargins& margins,
                                           int k, const std::atomic<bool>* cancel) const {
  const OptimizerSettings s = settingsFor(margins, k);
  RefinementCandidate c = solve(PlanOptimizer(model(), s), plan, cancel);
  c.label = k == 0 ? "first solve" : "retry with min_slip_rate " + std::to_string(s.min_slip_rate);
  return c;
}

}  // namespace rbsf::trajopt
