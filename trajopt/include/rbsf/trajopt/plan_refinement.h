#pragma once
/// \file
/// \brief The optimisation step of plan-reorientation and of the controller facade:
///        optimise an exact plan, certify the planner's plan and the optimised one
///        (plan/certificate.h), and keep the one with the better certificate.
///
/// The order: the planner's plan is certified; the optimiser refines it and, on success,
/// the refinement is certified; when that refinement is not certified, the optimiser runs
/// once more with OptimizerSettings::min_slip_rate = retry_min_slip_rate (sliding contacts
/// kept clearly sliding) and that refinement is certified too. The better certificate
/// wins (plan::betterCertificate): certified, then the higher lower confidence bound of the
/// success rate (sequential certificates of the candidates may stop after different numbers
/// of trials), then the smaller final error of its worst trial; on a tie the earlier
/// candidate (the planner's plan first) is kept.

#include <atomic>
#include <functional>
#include <string>

#include "rbsf/plan/certificate.h"
#include "rbsf/plan/refine_step.h"
#include "rbsf/trajopt/plan_optimizer.h"

namespace rbsf::trajopt {

/// \brief The plan to write and how it was chosen.
struct RefineOutcome {
  /// \brief The chosen plan with its `certificate` and the optimiser's `optimization`
  ///        summary (of the chosen solve, else of the first; `chosen`, `message`).
  plan::Plan plan;
  bool refined = false;  ///< the chosen plan is an optimised one
  /// \brief The solve summarised in plan.optimization converged (Ipopt's Solve_Succeeded or
  ///        Solved_To_Acceptable_Level).
  bool converged = false;
  std::string reason;  ///< why no optimised plan was chosen; empty when one was
  int attempts = 0;    ///< solves run (1, or 2 with the retry)
  /// \brief The planner's plan's certificate (also when an optimised plan is chosen).
  plan::Certificate planner_certificate;
};

/// \brief How refinePlan tries and judges.
struct RefineSettings {
  /// \brief Retry with this minimum slip rate [1/s] when the first refinement is not
  ///        certified (0 or the optimiser's own value: no retry).
  double retry_min_slip_rate = 0.1;
  plan::CertificateSettings certificate;  ///< how each candidate is certified
};

/// \brief Optimise, certify and choose (file comment). Every number in the summaries is
///        finite. A cancel (OptimizerSettings::cancel) stops after the current step: the
///        planner's plan is returned, certified if that had finished.
/// \throws InputError when the plan does not fit the optimiser's cell.
RefineOutcome refinePlan(const PlanOptimizer& optimizer, const plan::Plan& plan,
                         const RefineSettings& settings = {});

/// \brief The pipeline's refinement step (plan/refine_step.h, planner/reorientation_pipeline.h):
/// refinePlan with
///        `optimizer` (kept by reference: it must outlive the step) and the pipeline's
///        certificate settings; `report`, when given, sees every outcome.
plan::RefineStep refinementStep(const PlanOptimizer& optimizer,
                                std::function<void(const RefineOutcome&)> report = {});

}  // namespace rbsf::trajopt
