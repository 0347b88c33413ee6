#include "rbsf/planner/pipeline/reorientation_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"
#include "rbsf/planner/support/support_planner.h"
#include "rbsf/trajopt/plan_refinement.h"

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

/// One run of the pipeline: its attempts in order, the best record so far.
class PipelineRun {
 public:
  PipelineRun(const RbsfModel& model, const PipelineSettings& settings,
              const trajopt::PlanRefiner* refiner, const RunContext& context)
      : model_(model), s_(settings), refiner_(refiner), context_(context) {
    certificate_ = s_.certificate;
    out_.best_distance = std::numeric_limits<double>::infinity();
  }

  PipelineOutcome run(const Problem& problem) {
    certificate_.trial.position_tolerance = problem.tolerance.position;
    certificate_.trial.angle_tolerance = problem.tolerance.angle;
    if (s_.method != PipelineMethod::kKinodynamic) supportAttempt(problem);
    int attempts = 0;
    while (s_.method != PipelineMethod::kSupport && !cancelled() && !certified() &&
           (s_.max_attempts == 0 || attempts < s_.max_attempts)) {
      const double left = s_.planner.time_limit - since(t0_);
      if (attempts > 0 && left < s_.min_attempt_time) break;
      if (!kinodynamicAttempt(problem, attempts++, left)) break;
    }
    return finish();
  }

 private:
  bool cancelled() const { return context_.cancel != nullptr && context_.cancel->load(); }
  bool certified() const {
    return out_.chosen >= 0 && out_.attempts[out_.chosen].certificate.certified;
  }
  void emit(const PipelineEvent& event) const {
    if (context_.on_event) context_.on_event(event);
  }

  /// The support planner, with its share of the budget.
  void supportAttempt(const Problem& problem) {
    const Clock::time_point start = Clock::now();
    SupportPlannerSettings ss = s_.support;
    const double budget = s_.planner.time_limit;
    ss.time_limit = s_.method == PipelineMethod::kAuto ? s_.support_share * budget : budget;
    ss.feedback = s_.certificate.feedback;
    SupportPlanner support(model_, ss);
    PipelineAttempt a;
    a.search = SearchKind::kSupport;
    a.planner = "support";
    emit(StageStarted{PipelineStage::kSupportSearch, a});
    plan::Plan plan;
    const bool found = support.solve(problem, plan, context_.cancel);
    a.search_time = since(start);
    a.expansions = support.expansions();
    a.friction_use = support.frictionUse();
    a.paths_run = support.pathsRun();
    a.reach = support.reach();
    if (found && !cancelled())
      judge(a, std::move(plan), start, support.margins());
    else
      nothing(a, cancelled() ? "cancelled" : support.message());
  }

  /// Kinodynamic search `index` with `left` seconds of the budget; false: stop the run.
  bool kinodynamicAttempt(const Problem& problem, int index, double left) {
    const double budget = s_.planner.time_limit;
    // The first kinodynamic search always runs, with at least the budget the support
    // search left it; later ones only with min_attempt_time left.
    const double share =
        s_.method == PipelineMethod::kAuto ? (1.0 - s_.support_share) * budget : budget;
    const Clock::time_point start = Clock::now();
    PlannerSettings ps = s_.planner;
    ps.seed = s_.planner.seed + static_cast<std::uint32_t>(index);
    ps.time_limit = index == 0 ? std::max(left, share) : left;
    ReorientationPlanner search(model_, ps);
    PipelineAttempt a;
    a.planner = toString(ps.planner);
    a.seed = ps.seed;
    emit(StageStarted{PipelineStage::kKinodynamicSearch, a});
    plan::Plan plan;
    SearchContext search_context{context_.cancel, nullptr};
    if (context_.on_event)
      search_context.progress = [this](const Progress& p) { emit(SearchProgress{p}); };
    const bool found = search.solve(problem, plan, search_context);
    a.search_time = since(start);
    out_.best_distance = std::min(out_.best_distance, search.bestDistance());
    if (cancelled()) {
      // The path found so far is kept (not certified) when nothing better is.
      if (found && out_.chosen < 0) {
        a.found = true;
        a.exact = plan.status == plan::PlanStatus::kExact;
        out_.chosen = static_cast<int>(out_.attempts.size());
        best_.plan = std::move(plan);
      }
      a.note = "cancelled";
      a.cancelled = true;
      out_.attempts.push_back(a);
      return false;
    }
    if (found)
      judge(a, std::move(plan), start, plan::PlanMargins{});
    else
      nothing(a, "no path");
    return true;
  }

  /// Refine (when asked) and certify one attempt's plan; keep it when it is the best.
  void judge(PipelineAttempt& a, plan::Plan&& plan, Clock::time_point start,
             const plan::PlanMargins& margins) {
    a.found = true;
    a.exact = plan.status == plan::PlanStatus::kExact;
    emit(PlanFound{a, plan});
    plan::PlanRecord record;
    if (a.exact && refiner_ != nullptr) {
      emit(StageStarted{PipelineStage::kRefining, a});
      RefinementResult r =
          refineAndCertify(*refiner_, plan, margins, certificate_, context_.cancel);
      a.refined = r.refined;
      a.note = r.reason;
      emit(PlanRefined{a, r});
      record = std::move(r.record);
    } else {
      emit(StageStarted{PipelineStage::kCertifying, a});
      record.certificate = certify(model_, plan, certificate_, nullptr, context_.cancel);
      record.plan = std::move(plan);
    }
    if (cancelled()) record.certificate = {};
    a.certificate = record.certificate;
    a.phases = record.plan.phaseSequence();
    a.wall_time = since(start);
    emit(AttemptJudged{a, record});
    if (out_.chosen < 0 || betterPlan(a, out_.attempts[out_.chosen])) {
      out_.chosen = static_cast<int>(out_.attempts.size());
      best_ = std::move(record);
    }
    out_.attempts.push_back(a);
  }

  /// Record an attempt whose search found nothing.
  void nothing(PipelineAttempt& a, std::string note) {
    a.note = std::move(note);
    a.cancelled = cancelled();
    a.wall_time = a.search_time;
    emit(AttemptJudged{a, plan::PlanRecord{}});
    out_.attempts.push_back(a);
  }

  PipelineOutcome finish() {
    out_.wall_time = since(t0_);
    if (out_.chosen >= 0) {
      out_.record = std::move(best_);
      out_.record.plan.cell = plan::planCell(model_.cell());  // a controller checks it
    }
    const bool exact = out_.record.plan.status == plan::PlanStatus::kExact;
    if (cancelled()) {
      out_.status = PipelineStatus::kCancelled;
      out_.record.certificate = {};  // a cancelled run's certificate is not evidence
    } else if (out_.chosen < 0) {
      out_.status = PipelineStatus::kNoPlan;
    } else if (out_.record.certificate.certified) {
      out_.status = PipelineStatus::kCertified;
    } else {
      out_.status = exact ? PipelineStatus::kNotCertified : PipelineStatus::kApproximate;
    }
    return std::move(out_);
  }

  const RbsfModel& model_;
  const PipelineSettings& s_;
  const trajopt::PlanRefiner* refiner_;
  const RunContext& context_;
  plan::CertificateSettings certificate_;
  const Clock::time_point t0_ = Clock::now();
  PipelineOutcome out_;
  plan::PlanRecord best_;
};

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
  if (s.optimize) trajopt::PlanOptimizer(model_, s.optimizer);  // throws for bad settings
}

PipelineOutcome ReorientationPipeline::run(const Problem& problem, const RunContext& context) {
  ReorientationPlanner(model_, settings_.planner).checkProblem(problem);  // before any search
  std::optional<trajopt::PlanRefiner> refiner;
  if (settings_.optimize) refiner.emplace(model_, settings_.optimizer, settings_.refine);
  PipelineRun run(model_, settings_, refiner ? &*refiner : nullptr, context);
  return run.run(problem);
}

}  // namespace rbsf::planner
