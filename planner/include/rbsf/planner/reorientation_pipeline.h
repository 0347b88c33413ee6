#pragma once
/// \file
/// \brief Plan, refine and certify until a plan certifies or the time limit is spent: the
///        one composition of the planners, the optimiser and the certificate that the
///        command-line tool, the controller facade and the benchmarks share.
///
/// The order of attempts (Method::kAuto): the support planner first (support_planner.h:
/// slow supports held by the joints, its own ladder of friction margins), then the
/// kinodynamic planner (reorientation_planner.h) with seeds planner.seed, planner.seed + 1,
/// ... Every exact plan goes through `refine` when one is given (the optimiser and its
/// choice, trajopt/plan_refinement.h; a support plan with the margins it was planned with,
/// plan::PlanMargins); every plan is certified (certificate.h).
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
#include <vector>

#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan.h"
#include "rbsf/plan/refine_step.h"
#include "rbsf/planner/planner_settings.h"
#include "rbsf/planner/support_planner.h"

namespace rbsf::planner {

/// \brief What the pipeline is doing (the progress line names it).
enum class PipelineStage { kSupportSearch, kKinodynamicSearch, kRefining, kCertifying };

/// \brief "searching supports", "searching (KPIECE1, seed 3)", "optimising", "certifying".
std::string stageText(PipelineStage stage, const std::string& method, std::uint32_t seed);

/// \brief How a pipeline run ended.
enum class PipelineStatus {
  kCertified,     ///< the plan is certified
  kNotCertified,  ///< an exact plan, none certified within the budget
  kApproximate,   ///< no exact plan: the closest approach (with its certificate)
  kNoPlan,        ///< no path at all: nothing to write
  kCancelled,     ///< stopped by planner.cancel: the best plan so far (may be empty)
};

/// \brief "certified", "not certified", "approximate", "no plan", "cancelled".
const char* statusText(PipelineStatus status);

/// \brief One attempt: a search and, when it found a path, its plan's certificate.
struct PipelineAttempt {
  std::string method;             ///< "support" or the kinodynamic planner's name
  std::uint32_t seed = 0;         ///< the kinodynamic planner's seed (0 for support)
  bool found = false;             ///< a path (exact or approximate)
  bool exact = false;             ///< the plan reaches the goal
  bool refined = false;           ///< the optimised plan was kept
  double search_time = 0.0;       ///< wall time of the search [s]
  double wall_time = 0.0;         ///< search, refinement and certificate [s]
  long expansions = 0;            ///< the support search's expansions, every margin
  double friction_use = 0.0;      ///< the support path's friction use (support_planner.h)
  int paths_run = 0;              ///< support paths found and run (support_planner.h)
  SupportReach reach;             ///< what the support searches reached (support_reach.h)
  std::string phases;             ///< Plan::phaseSequence() of the attempt's plan
  plan::Certificate certificate;  ///< of the attempt's plan (ran false when none)
  std::string note;               ///< why the search found nothing, or the refinement's reason
};

/// \brief Settings of ReorientationPipeline; defaults documented.
struct PipelineSettings {
  /// \brief Which planners: kAuto (support, then kinodynamic), kSupport or kKinodynamic.
  enum class Method { kAuto, kSupport, kKinodynamic };
  Method method = Method::kAuto;
  /// \brief The kinodynamic planner; time_limit is the whole run's search budget [s],
  ///        seed the first attempt's seed; tolerances, cancel and progress serve every stage.
  PlannerSettings planner;
  /// \brief The support planner (its time_limit, tolerances and cancel are set from
  ///        `planner`).
  SupportPlannerSettings support;
  double support_share = 0.5;     ///< kAuto: the support search's share of the budget
  int max_attempts = 0;           ///< kinodynamic searches at most (0: while the budget lasts)
  double min_attempt_time = 1.0;  ///< [s] no later kinodynamic search starts with less left
  /// \brief The trials (tolerances are set from `planner`; feedback as given).
  plan::CertificateSettings certificate;
  /// \brief The refinement of each exact plan (trajopt::refinementStep); empty: plans are
  ///        certified as found.
  plan::RefineStep refine;
  /// \brief Called when a stage starts (progress lines).
  std::function<void(PipelineStage, const std::string& method, std::uint32_t seed)> on_stage;
  /// \brief Called when a search has found a plan, before it is refined and certified.
  std::function<void(const PipelineAttempt&, const plan::Plan&)> on_found;
  /// \brief Called when an attempt has been judged (or found nothing), with its plan (report
  /// lines).
  std::function<void(const PipelineAttempt&, const plan::Plan&)> on_attempt;
};

/// \brief The result of a run: the plan to write and how it was found.
struct PipelineOutcome {
  PipelineStatus status = PipelineStatus::kNoPlan;
  plan::Plan plan;  ///< the best plan (empty when status is kNoPlan)
  std::vector<PipelineAttempt> attempts;
  int chosen = -1;  ///< index in attempts of the plan kept (-1: none)
  /// \brief The kinodynamic searches' smallest goal distance (tolerance units; infinity
  ///        when none ran).
  double best_distance = 0.0;
  double wall_time = 0.0;  ///< [s]
};

/// \brief Plan, refine and certify (file comment); one per thread.
class ReorientationPipeline {
 public:
  /// \throws InputError for bad settings (an unknown planner name, a non-positive budget).
  ReorientationPipeline(const RbsfModel& model, PipelineSettings settings);

  /// \brief Run the attempts for `problem`.
  /// \throws InputError when the problem is bad (checkProblem), before any search.
  PipelineOutcome run(const Problem& problem);

  const PipelineSettings& settings() const { return settings_; }

 private:
  const RbsfModel& model_;
  PipelineSettings settings_;
};

}  // namespace rbsf::planner
