#include "rbsf/trajopt/plan_refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

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

bool cancelled(const PlanOptimizer& o) {
  return o.settings().cancel != nullptr && o.settings().cancel->load();
}

/// One solve: its plan (when it succeeded and is finite) and its summary.
struct Attempt {
  bool usable = false;
  bool converged = false;  ///< Ipopt converged
  plan::Plan plan;
  plan::OptimizationSummary summary;
  std::string reason;  ///< why it is not usable
};

Attempt solve(const PlanOptimizer& optimizer, const plan::Plan& plan) {
  Attempt a;
  OptimizedPlan opt = optimizer.optimize(plan);
  a.summary = opt.plan.optimization;
  a.summary.ran = true;
  a.converged = opt.success;
  std::string note;
  finite(a.summary.solve_time, "solve_time", note);
  finite(a.summary.cost_before, "cost_before", note);
  finite(a.summary.cost_after, "cost_after", note);
  if (!opt.success) {
    a.reason = "optimisation failed (Ipopt status " + a.summary.status + ")";
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
  base.tube_position = support.tube_position;
  base.tube_angle = support.tube_angle;
  base.duration_min_scale = support.duration_min_scale;
  return base;
}

bool atLeastAsGood(const plan::Certificate& a, const plan::Certificate& b) {
  return a.ran && (a.certified || !b.certified) && a.lower_bound >= b.lower_bound;
}

RefineOutcome refinePlan(const PlanOptimizer& given, const plan::Plan& plan,
                         const RefineSettings& settings, const plan::PlanMargins& margins) {
  // A support plan is refined by an optimiser of the same cell with its margins.
  std::unique_ptr<PlanOptimizer> support;
  if (margins.support)
    support = std::make_unique<PlanOptimizer>(
        given.model(), supportOptimizerSettings(given.settings(), margins, settings.support));
  const PlanOptimizer& optimizer = support ? *support : given;
  const RbsfModel& model = optimizer.model();
  const std::atomic<bool>* cancel = optimizer.settings().cancel;
  RefineOutcome out;
  out.plan = plan;
  out.planner_certificate = plan::certify(model, plan, settings.certificate, nullptr, cancel);
  out.plan.certificate = out.planner_certificate;

  std::vector<Attempt> attempts;
  std::vector<plan::Certificate> certificates;
  auto attempt = [&](const PlanOptimizer& o) {
    attempts.push_back(solve(o, plan));
    certificates.emplace_back();
    Attempt& a = attempts.back();
    if (a.usable && !cancelled(o)) {
      certificates.back() = plan::certify(model, a.plan, settings.certificate, nullptr, cancel);
      a.summary.refined_success_rate = certificates.back().success_rate;
    }
  };
  if (!cancelled(optimizer)) attempt(optimizer);
  // The retry changes the slip floor: to retry_min_slip_rate, or from it to none (a floor on
  // every interval of a slide can leave no path inside a support plan's tube).
  const double first = optimizer.settings().min_slip_rate;
  const double retry = first == settings.retry_min_slip_rate ? 0.0 : settings.retry_min_slip_rate;
  if (!attempts.empty() && !certificates.back().certified && !cancelled(optimizer) &&
      settings.retry_min_slip_rate > 0.0 && retry != first) {
    OptimizerSettings again = optimizer.settings();
    again.min_slip_rate = retry;
    attempt(PlanOptimizer(model, again));
  }
  out.attempts = static_cast<int>(attempts.size());
  if (attempts.empty()) return out;

  // The better refinement, then against the planner's plan (file comment).
  int best = -1;
  for (int k = 0; k < out.attempts; ++k) {
    if (!certificates[k].ran) continue;
    if (best < 0 || plan::betterCertificate(certificates[k], certificates[best])) best = k;
  }
  if (best >= 0 && !atLeastAsGood(certificates[best], out.planner_certificate)) best = -1;
  std::ostringstream why;
  for (int k = 0; k < out.attempts; ++k) {
    if (k == best) continue;
    why << (why.tellp() > 0 ? "; " : "")
        << (k == 0 ? "first solve" : "retry with min_slip_rate " + std::to_string(retry)) << ": ";
    if (!attempts[k].usable)
      why << attempts[k].reason;
    else if (!certificates[k].ran)
      why << "not certified (cancelled)";
    else
      why << "its certificate is "
          << (best < 0
                  ? std::string("short of the planner's plan's (") +
                        (out.planner_certificate.certified ? "certified, " : "") + "lower bound " +
                        std::to_string(out.planner_certificate.lower_bound) + ")"
                  : std::string("not better than the chosen one's"))
          << ": " << plan::verdictText(certificates[k]);
  }
  const int summary = best < 0 ? 0 : best;
  if (best >= 0) {
    out.plan = std::move(attempts[best].plan);
    out.plan.certificate = certificates[best];
    out.refined = true;
  } else {
    out.reason = why.str();
  }
  out.plan.optimization = attempts[summary].summary;
  out.converged = attempts[summary].converged;
  out.plan.optimization.chosen = out.refined;
  out.plan.optimization.message = why.str();
  return out;
}

plan::RefineStep refinementStep(const PlanOptimizer& optimizer,
                                std::function<void(const RefineOutcome&)> report) {
  return [&optimizer, report = std::move(report)](
             const plan::Plan& plan, const plan::PlanMargins& margins,
             const plan::CertificateSettings& certificate, bool& refined, std::string& note) {
    RefineSettings settings;
    settings.certificate = certificate;
    RefineOutcome r = refinePlan(optimizer, plan, settings, margins);
    if (report) report(r);
    refined = r.refined;
    note = r.reason;
    return std::move(r.plan);
  };
}

}  // namespace rbsf::trajopt
