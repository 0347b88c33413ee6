#pragma once
/// \file
/// \brief The optimisation step of plan-reorientation and of the controller facade:
///        optimise an exact plan, certify the planner's plan and the optimised one
///        (plan/certificate.h), and keep the one with the better certificate.
///
/// The order: the planner's plan is certified; the optimiser refines it and, on success,
/// the refinement is certified; when that refinement is not certified, the optimiser runs
/// once more with OptimizerSettings::min_slip_rate = retry_min_slip_rate (sliding contacts
/// kept clearly sliding; when the first solve had that floor already, as a support plan's
/// does, with none) and that refinement is certified too. Of the refinements the
/// better certificate wins (plan::betterCertificate: certified, then the higher lower
/// confidence bound of the success rate, then the smaller final error of its worst trial;
/// the first on a tie). It is written instead of the planner's plan when its certificate is
/// at least as good on the verdict and on the bound (atLeastAsGood): certified if the
/// planner's is, and a lower bound at least the planner's. The refinement is chosen on a
/// tie: it carries the plan with less effort.
///
/// A support plan (plan::PlanMargins::support) is refined on its stated roles with the
/// margins it was planned with, the cell's motion limits and a tube around its path
/// (supportOptimizerSettings): the refinements that minimised effort freely removed the
/// squeeze and the margins that kept its contacts in their roles, and every one dropped the
/// part.

#include <atomic>
#include <cmath>
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

/// \brief How a support plan is refined beyond its margins (supportOptimizerSettings).
struct SupportRefinement {
  /// \brief The tube around the planner's path (OptimizerSettings::tube_position,
  ///        tube_angle): the goal's tolerances. With no tube the 30 degree plan's refinement
  ///        lifted the part 25 cm and dropped it in every trial.
  double tube_position = 0.01;             ///< [m]
  double tube_angle = 2.0 * M_PI / 180.0;  ///< [rad]
  double duration_min_scale = 0.5;         ///< runs may take half their planned time
  /// \brief OptimizerSettings::min_slip_rate of the first solve [1/s]: none (the slides
  ///        keep their direction only). A floor on every interval of a slide left no
  ///        refinement inside the tube for the 45 degree plan, and for the 30 degree plan
  ///        with runs of at least 0.7 of their time; the law keeps loose sliders slipping by
  ///        itself. RefineSettings::retry_min_slip_rate asks for it in the retry.
  double min_slip_rate = 0.0;
};

/// \brief How refinePlan tries and judges.
struct RefineSettings {
  /// \brief Retry with this minimum slip rate [1/s] when the first refinement is not
  ///        certified; when the first solve had this rate, the retry has none (0: no
  ///        retry).
  double retry_min_slip_rate = 0.1;
  plan::CertificateSettings certificate;  ///< how each candidate is certified
  SupportRefinement support;              ///< for support plans
};

/// \brief The optimiser's settings for a support plan planned with `margins`: `base` with
///        runs on the stated roles, the sticking forces within margins.friction_use of the
///        cone, relied-on normal forces above margins.normal_margin of the part's weight,
///        the slides kept one way (at least at `support.min_slip_rate`), the cell's motion
///        limits, the least-norm internal forces and `support`'s tube and shortest runs.
OptimizerSettings supportOptimizerSettings(OptimizerSettings base, const plan::PlanMargins& margins,
                                           const SupportRefinement& support = {});

/// \brief True when certificate `a` is at least as good as `b` on the verdict and on the
///        bound: `a` ran, is certified when `b` is, and its lower bound is at least `b`'s.
bool atLeastAsGood(const plan::Certificate& a, const plan::Certificate& b);

/// \brief Optimise, certify and choose (file comment). Every number in the summaries is
///        finite. A cancel (OptimizerSettings::cancel) stops after the current step: the
///        planner's plan is returned, certified if that had finished.
/// \throws InputError when the plan does not fit the optimiser's cell.
///        A support plan (margins.support) is refined with
///        supportOptimizerSettings(optimizer.settings(), margins, settings.support).
RefineOutcome refinePlan(const PlanOptimizer& optimizer, const plan::Plan& plan,
                         const RefineSettings& settings = {},
                         const plan::PlanMargins& margins = {});

/// \brief The pipeline's refinement step (plan/refine_step.h, planner/reorientation_pipeline.h):
/// refinePlan with
///        `optimizer` (kept by reference: it must outlive the step) and the pipeline's
///        certificate settings; `report`, when given, sees every outcome.
plan::RefineStep refinementStep(const PlanOptimizer& optimizer,
                                std::function<void(const RefineOutcome&)> report = {});

}  // namespace rbsf::trajopt
