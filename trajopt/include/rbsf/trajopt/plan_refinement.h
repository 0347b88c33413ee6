#pragma once
/// \file
/// \brief The optimiser's candidates for an exact plan: the refinements the pipeline
///        certifies and chooses between (planner/refine_and_certify.h).
///
/// The first candidate is the plan optimised with the refiner's settings; the second, the
/// retry, is asked for when the first is not certified: the same solve with
/// OptimizerSettings::min_slip_rate = retry_min_slip_rate (sliding contacts kept clearly
/// sliding; when the first solve had that floor already, with none).
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

#include "rbsf/plan/plan_margins.h"
#include "rbsf/trajopt/plan_optimizer.h"

namespace rbsf::trajopt {

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

/// \brief How the refiner makes its candidates.
struct RefineSettings {
  /// \brief Retry with this minimum slip rate [1/s] when the first refinement is not
  ///        certified; when the first solve had this rate, the retry has none (0: no
  ///        retry).
  double retry_min_slip_rate = 0.1;
  SupportRefinement support;  ///< for support plans
};

/// \brief The optimiser's settings for a support plan planned with `margins`: `base` with
///        runs on the stated roles, the sticking forces within margins.friction_use of the
///        cone, relied-on normal forces above margins.normal_margin of the part's weight,
///        the slides kept one way (at least at `support.min_slip_rate`), the cell's motion
///        limits, the least-norm internal forces, the plan's end rest kept (keep_end_rest)
///        and `support`'s tube and shortest runs.
OptimizerSettings supportOptimizerSettings(OptimizerSettings base, const plan::PlanMargins& margins,
                                           const SupportRefinement& support = {});

/// \brief One optimised candidate of a plan, not yet certified.
struct RefinementCandidate {
  /// \brief The solve succeeded and its plan holds finite numbers only: `plan` is the
  ///        refinement. false: `reason` says why, `plan` is empty.
  bool usable = false;
  bool converged = false;  ///< Ipopt converged (plan::converged(summary.status))
  plan::Plan plan;
  plan::OptimizationSummary summary;  ///< every number finite (a non-finite one written as 0)
  std::string reason;                 ///< why it is not usable
  std::string label;                  ///< "first solve" or "retry with min_slip_rate <rate>"
};

/// \brief The optimiser's candidates for the plans of one cell (file comment).
class PlanRefiner {
 public:
  /// \throws InputError for bad optimiser settings.
  PlanRefiner(const RbsfModel& model, OptimizerSettings settings, RefineSettings refine = {});

  /// \brief How many candidates a plan with `margins` may have: 1, or 2 with the retry.
  int candidates(const plan::PlanMargins& margins) const;
  /// \brief Candidate `k` (0: the first solve, 1: the retry) of `plan`. A support plan
  ///        (margins.support) is solved with supportOptimizerSettings(settings(), margins,
  ///        refine.support); `cancel` stops its solve (PlanOptimizer::optimize).
  ///        \throws InputError when the plan does not fit the cell.
  RefinementCandidate candidate(const plan::Plan& plan, const plan::PlanMargins& margins, int k,
                                const std::atomic<bool>* cancel = nullptr) const;

  const RbsfModel& model() const { return optimizer_.model(); }
  const OptimizerSettings& settings() const { return optimizer_.settings(); }

 private:
  /// \brief The optimiser's settings of candidate `k` of a plan with `margins`.
  OptimizerSettings settingsFor(const plan::PlanMargins& margins, int k) const;
  PlanOptimizer optimizer_;  ///< the cell and the settings, checked when made
  RefineSettings refine_;
};

}  // namespace rbsf::trajopt
