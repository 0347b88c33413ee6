#pragma once
/// \file
/// \brief Plan, refine and certify until a plan certifies or the time limit is spent: the
///        one composition of the planners, the optimiser and the certificate that the
///        command-line tool, the controller facade and the benchmarks share; they only
///        translate its settings, events and outcome.
///
/// The order of attempts (Method::kAuto): the support planner first (support_planner.h:
/// slow supports held by the joints, its own ladder of friction margins), then the
/// kinodynamic planner (reorientation_planner.h) with seeds planner.seed, planner.seed + 1,
/// ... With `optimize`, every exact plan is refined and the better of it and its refinements
/// kept (refine_and_certify.h: the optimiser's candidates, trajopt/plan_refinement.h; a
/// support plan with the margins it was planned with, plan::PlanMargins); every plan is
/// certified (certificate.h), here alone. The result is a plan::PlanRecord: the plan, its
/// certificate and its optimisation summary.
/// The first certified plan ends the run. Otherwise attempts go on while the planning
/// budget (planner.time_limit, all attempts' searches) lasts, and the best plan is kept:
/// Certificate ranking (betterCertificate), an exact plan before an approximate one.
///
/// The budget bounds the searches; the refinement and certificate of a plan found within it
/// run to their end (their own limits). The first kinodynamic search always runs, with at
/// least the share the support search leaves it; no later one starts with less than
/// min_attempt_time left.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/planner/pipeline/refine_and_certify.h"
#include "rbsf/planner/planner_settings.h"
#include "rbsf/planner/support/support_planner.h"
#include "rbsf/trajopt/optimizer_settings.h"
#include "rbsf/trajopt/plan_refinement.h"

namespace rbsf::planner {

/// \brief What the pipeline is doing (the progress line names it).
enum class PipelineStage { kSupportSearch, kKinodynamicSearch, kRefining, kCertifying };

/// \brief "searching supports", "searching (KPIECE1, seed 3)", "optimising and certifying
///        the support plan", "certifying the KPIECE1 plan".
std::string stageText(PipelineStage stage, const std::string& method, std::uint32_t seed);

/// \brief How a pipeline run ended.
enum class PipelineStatus {
  kCertified,     ///< the plan is certified
  kNotCertified,  ///< an exact plan, none certified within the budget
  kApproximate,   ///< no exact plan: the closest approach (with its certificate)
  kNoPlan,        ///< no path at all: nothing to write
  kCancelled,     ///< stopped by the run's cancel flag: the best plan so far (may be empty)
};

/// \brief "certified", "not certified", "approximate", "no plan", "cancelled".
const char* statusText(PipelineStatus status);

/// \brief Which planners a run tries: kAuto (support, then kinodynamic), kSupport or
///        kKinodynamic.
enum class PipelineMethod { kAuto, kSupport, kKinodynamic };

/// \brief Which search an attempt ran.
enum class SearchKind { kSupport, kKinodynamic };

/// \brief One attempt: a search and, when it found a path, its plan's certificate.
struct PipelineAttempt {
  SearchKind search = SearchKind::kKinodynamic;
  std::string planner;            ///< the kinodynamic planner's name ("support" for support)
  std::uint32_t seed = 0;         ///< the kinodynamic planner's seed (0 for support)
  bool found = false;             ///< a path (exact or approximate)
  bool exact = false;             ///< the plan reaches the goal
  bool refined = false;           ///< the optimised plan was kept
  bool cancelled = false;         ///< the run's cancel flag stopped it
  double search_time = 0.0;       ///< wall time of the search [s]
  double wall_time = 0.0;         ///< search, refinement and certificate [s]
  long expansions = 0;            ///< the support search's expansions, every margin
  double friction_use = 0.0;      ///< the support path's friction use (support_planner.h)
  int paths_run = 0;              ///< support paths found and run (support_planner.h)
  SupportReach reach;             ///< what the support searches reached (support_reach.h)
  std::string phases;             ///< Plan::phaseSequence() of the attempt's plan
  plan::Certificate certificate;  ///< of the attempt's plan (ran false when none)
  /// \brief Why the search found nothing, or why no refinement was kept; empty otherwise.
  std::string note;
  /// \brief "support" or the kinodynamic planner's name.
  const std::string& method() const { return planner; }
};

/// \brief A stage starts (progress lines).
struct StageStarted {
  PipelineStage stage;
  const PipelineAttempt& attempt;
};
/// \brief A kinodynamic search's progress, about once per second.
struct SearchProgress {
  const Progress& progress;
};
/// \brief A search found a plan, before it is refined and certified.
struct PlanFound {
  const PipelineAttempt& attempt;
  const plan::Plan& plan;
};
/// \brief An exact plan was refined and the better plan chosen (refine_and_certify.h).
struct PlanRefined {
  const PipelineAttempt& attempt;
  const RefinementResult& refinement;
};
/// \brief An attempt ended: judged (its record certified), or its search found nothing
///        (record empty, attempt.note says why).
struct AttemptJudged {
  const PipelineAttempt& attempt;
  const plan::PlanRecord& record;
};
/// \brief The pipeline's typed event stream, in the order above within each attempt.
using PipelineEvent =
    std::variant<StageStarted, SearchProgress, PlanFound, PlanRefined, AttemptJudged>;

/// \brief What a caller gives one run besides its settings: the cancel flag (set from
///        another thread or a signal handler: every stage stops at its next check, the
///        search's best plan so far is kept, not certified) and the event stream.
struct RunContext {
  const std::atomic<bool>* cancel = nullptr;
  std::function<void(const PipelineEvent&)> on_event;  ///< on the run's thread
};

/// \brief Settings of ReorientationPipeline; defaults documented. The pipeline writes the
///        budget and the feedback into the stages' settings, and the problem's tolerance
///        into the certificate's criteria.
struct PipelineSettings {
  PipelineMethod method = PipelineMethod::kAuto;
  /// \brief The kinodynamic planner; time_limit is the whole run's search budget [s],
  ///        seed the first attempt's seed (cancel and progress come from the RunContext).
  PlannerSettings planner;
  /// \brief The support planner (its time_limit and feedback are set by the pipeline; its
  ///        cancel flag is the RunContext's).
  SupportPlannerSettings support;
  double support_share = 0.5;     ///< kAuto: the support search's share of the budget
  int max_attempts = 0;           ///< kinodynamic searches at most (0: while the budget lasts)
  double min_attempt_time = 1.0;  ///< [s] no later kinodynamic search starts with less left
  /// \brief The trials (their tolerances are the problem's); its `feedback`, the control
  ///        law's gains, is also the support planner's for its closed-loop runs.
  plan::CertificateSettings certificate;
  /// \brief Refine every exact plan with the optimiser (refine_and_certify.h); false: plans
  ///        are certified as found.
  bool optimize = false;
  trajopt::OptimizerSettings optimizer;  ///< its cancel comes from the RunContext
  trajopt::RefineSettings refine;        ///< the retry and the support plans' tube
};

/// \brief The result of a run: the record to write and how it was found.
struct PipelineOutcome {
  PipelineStatus status = PipelineStatus::kNoPlan;
  /// \brief The best plan with its certificate (none when cancelled) and optimisation
  ///        summary; empty when status is kNoPlan.
  plan::PlanRecord record;
  std::vector<PipelineAttempt> attempts;
  int chosen = -1;  ///< index in attempts of the plan kept (-1: none)
  /// \brief The kinodynamic searches' smallest goal distance (tolerance units; infinity
  ///        when none ran).
  double best_distance = 0.0;
  double wall_time = 0.0;  ///< [s]
  /// \brief The attempt whose plan was kept, or nullptr.
  const PipelineAttempt* chosenAttempt() const {
    return chosen >= 0 ? &attempts[static_cast<std::size_t>(chosen)] : nullptr;
  }
};

/// \brief Plan, refine and certify (file comment); one run at a time.
class ReorientationPipeline {
 public:
  /// \throws InputError for bad settings (an unknown planner name, a non-positive budget,
  ///         bad optimiser settings).
  ReorientationPipeline(const RbsfModel& model, PipelineSettings settings);

  /// \brief Run the attempts for `problem`.
  /// \throws InputError when the problem is bad (checkProblem), before any search.
  PipelineOutcome run(const Problem& problem, const RunContext& context = {});

  const PipelineSettings& settings() const { return settings_; }

 private:
  const RbsfModel& model_;
  PipelineSettings settings_;
};

}  // namespace rbsf::planner
