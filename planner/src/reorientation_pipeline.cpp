#include "rbsf/planner/reorientation_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "rbsf/dynamics/errors.h"
#include "rbsf/planner/reorientation_planner.h"
#include "rbsf/planner/support_planner.h"

namespace rbsf::planner {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// An exact plan before an approximate one, then the better certificate.
bool betterPlan(const PipelineAttempt& a, const PipelineAttempt& b) {
  if (a.certificate.certified != b.certificate.certified) return a.certificate.certified;
  if (a.exact != b.exact) return a.exact;
  return betterCertificate(a.certificate, b.certificate);
}

}  // namespace

std::string stageText(PipelineStage stage, const std::string& method, std::uint32_t seed) {
  switch (stage) {
    case PipelineStage::kSupportSearch:
      return "searching supports";
    case PipelineStage::kKinodynamicSearch:
      return "searching (" + method + ", seed " + std::to_string(seed) + ")";
    case PipelineStage::kRefining:
      return "optimising and certifying the " + method + " plan";
    case PipelineStage::kCertifying:
      return "certifying the " + method + " plan";
  }
  return "";
}

const char* statusText(PipelineStatus status) {
  switch (status) {
    case PipelineStatus::kCertified:
      return "certified";
    case PipelineStatus::kNotCertified:
      return "not certified";
    case PipelineStatus::kApproximate:
      return "approximate";
    case PipelineStatus::kNoPlan:
      return "no plan";
    case PipelineStatus::kCancelled:
      return "cancelled";
  }
  return "";
}

ReorientationPipeline::ReorientationPipeline(const RbsfModel& model, PipelineSettings settings)
    : model_(model), settings_(std::move(settings)) {
  const PipelineSettings& s = settings_;
  // Every stage's settings, before any work: a bad one never costs a search.
  checkSettings(s.planner);
  checkSettings(s.certificate);
  if (!(s.support_share > 0.0 && s.support_share <= 1.0))
    throw InputError("support share: must be in (0, 1]");
  if (s.max_attempts < 0) throw InputError("max attempts: must be 0 (no limit) or positive");
  if (!(s.min_attempt_time >= 0.0) || !std::isfinite(s.min_attempt_time))
    throw InputError("min attempt time: must be finite and not negative");
}

PipelineOutcome ReorientationPipeline::run(const Problem& problem) {
  const PipelineSettings& s = settings_;
  const Clock::time_point t0 = Clock::now();
  const double budget = s.planner.time_limit;
  auto cancelled = [&] { return s.planner.cancel != nullptr && s.planner.cancel->load(); };
  auto stage = [&](PipelineStage st, const std::string& method, std::uint32_t seed) {
    if (s.on_stage) s.on_stage(st, method, seed);
  };
  ReorientationPlanner kinodynamic(model_, s.planner);
  kinodynamic.checkProblem(problem);  // bad input before any search

  plan::CertificateSettings certificate = s.certificate;
  certificate.trial.position_tolerance = s.planner.position_tolerance;
  certificate.trial.angle_tolerance = s.planner.angle_tolerance;

  PipelineOutcome out;
  out.best_distance = std::numeric_limits<double>::infinity();
  plan::Plan best;
  // Judge one attempt's plan (refine, certify), keep it when it is the best so far.
  auto judge = [&](PipelineAttempt& a, plan::Plan&& plan, Clock::time_point start,
                   const plan::PlanMargins& margins) {
    a.found = true;
    a.exact = plan.status == plan::PlanStatus::kExact;
    if (s.on_found) s.on_found(a, plan);
    if (a.exact && s.refine) {
      stage(PipelineStage::kRefining, a.method, a.seed);
      plan = s.refine(plan, margins, certificate, a.refined, a.note);
    } else {
      stage(PipelineStage::kCertifying, a.method, a.seed);
      plan.certificate = certify(model_, plan, certificate, nullptr, s.planner.cancel);
    }
    if (cancelled()) plan.certificate = {};
    a.certificate = plan.certificate;
    a.phases = plan.phaseSequence();
    a.wall_time = since(start);
    if (s.on_attempt) s.on_attempt(a, plan);
    if (out.chosen < 0 || betterPlan(a, out.attempts[out.chosen])) {
      out.chosen = static_cast<int>(out.attempts.size());
      best = std::move(plan);
    }
    out.attempts.push_back(a);
  };
  // Record an attempt whose search found nothing.
  auto nothing = [&](PipelineAttempt& a, const plan::Plan& plan, std::string note) {
    a.note = std::move(note);
    a.wall_time = a.search_time;
    if (s.on_attempt) s.on_attempt(a, plan);
    out.attempts.push_back(a);
  };

  using Method = PipelineSettings::Method;
  if (s.method != Method::kKinodynamic) {
    const Clock::time_point start = Clock::now();
    SupportPlannerSettings ss = s.support;
    ss.time_limit = s.method == Method::kAuto ? s.support_share * budget : budget;
    ss.position_tolerance = s.planner.position_tolerance;
    ss.angle_tolerance = s.planner.angle_tolerance;
    ss.cancel = s.planner.cancel;
    SupportPlanner support(model_, ss);
    PipelineAttempt a;
    a.method = "support";
    stage(PipelineStage::kSupportSearch, a.method, 0);
    plan::Plan plan;
    const bool found = support.solve(problem, plan);
    a.search_time = since(start);
    a.expansions = support.expansions();
    a.friction_use = support.frictionUse();
    a.paths_run = support.pathsRun();
    a.reach = support.reach();
    if (found && !cancelled()) {
      judge(a, std::move(plan), start, support.margins());
    } else {
      nothing(a, plan, cancelled() ? "cancelled" : support.message());
    }
  }
  int kinodynamic_attempts = 0;
  std::uint32_t seed = s.planner.seed;
  while (s.method != Method::kSupport && !cancelled() &&
         !(out.chosen >= 0 && out.attempts[out.chosen].certificate.certified) &&
         (s.max_attempts == 0 || kinodynamic_attempts < s.max_attempts)) {
    const double left = budget - since(t0);
    // The first kinodynamic search always runs, with at least the budget the support
    // search left it; later ones only with min_attempt_time left.
    const double share = s.method == Method::kAuto ? (1.0 - s.support_share) * budget : budget;
    if (kinodynamic_attempts > 0 && left < s.min_attempt_time) break;
    const Clock::time_point start = Clock::now();
    PlannerSettings ps = s.planner;
    ps.seed = seed;
    ps.time_limit = kinodynamic_attempts == 0 ? std::max(left, share) : left;
    ReorientationPlanner search(model_, ps);
    PipelineAttempt a;
    a.method = ps.planner;
    a.seed = seed;
    stage(PipelineStage::kKinodynamicSearch, a.method, seed);
    plan::Plan plan;
    const bool found = search.solve(problem, plan);
    a.search_time = since(start);
    out.best_distance = std::min(out.best_distance, search.bestDistance());
    ++kinodynamic_attempts;
    ++seed;
    if (cancelled()) {
      // The path found so far is kept (not certified) when nothing better is.
      if (found && out.chosen < 0) {
        a.found = true;
        a.exact = plan.status == plan::PlanStatus::kExact;
        out.chosen = static_cast<int>(out.attempts.size());
        best = std::move(plan);
      }
      a.note = "cancelled";
      out.attempts.push_back(a);
      break;
    }
    if (found) {
      judge(a, std::move(plan), start, plan::PlanMargins{});
    } else {
      nothing(a, plan, "no path");
    }
  }

  out.wall_time = since(t0);
  if (out.chosen >= 0) {
    out.plan = std::move(best);
    out.plan.cell = plan::planCell(model_.cell());  // a controller checks it (plan_fit.h)
  }
  if (cancelled())
    out.status = PipelineStatus::kCancelled;
  else if (out.chosen < 0)
    out.status = PipelineStatus::kNoPlan;
  else if (out.plan.certificate.certified)
    out.status = PipelineStatus::kCertified;
  else if (out.plan.status == plan::PlanStatus::kExact)
    out.status = PipelineStatus::kNotCertified;
  else
    out.status = PipelineStatus::kApproximate;
  return out;
}

}  // namespace rbsf::planner
