#pragma once
/// \file
/// \brief Refine an exact plan and keep the better of it and its refinements, by their
///        certificates: the pipeline's judgement of a plan (reorientation_pipeline.h).
///
/// The order: the planner's plan is certified; the refiner's first candidate
/// (trajopt/plan_refinement.h) is certified when usable; when it is not certified and the
/// refiner offers a retry, the retry is certified too. Of the refinements the better
/// certificate wins (plan::betterCertificate: certified, then the higher lower confidence
/// bound of the success rate, then the smaller final error of its worst trial; the first on
/// a tie). It is kept instead of the planner's plan when its certificate is at least as
/// good on the verdict and on the bound (atLeastAsGood). The refinement is chosen on a tie:
/// it carries the plan with less effort.

#include <string>

#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/plan/plan_margins.h"
#include "rbsf/trajopt/plan_refinement.h"

namespace rbsf::planner {

/// \brief The plan kept, with its certificate and the optimiser's summary, and how it was
///        chosen.
struct RefinementResult {
  /// \brief The chosen plan with its certificate, and the summary of the chosen solve
  ///        (else of the first; its `chosen` and `message` say which and why).
  plan::PlanRecord record;
  bool refined = false;    ///< the chosen plan is an optimised one
  bool converged = false;  ///< the solve summarised converged
  std::string reason;      ///< why no optimised plan was chosen; empty when one was
  int solves = 0;          ///< candidates solved (1, or 2 with the retry)
  /// \brief The planner's plan's certificate (also when an optimised plan is chosen).
  plan::Certificate planner_certificate;
};

/// \brief True when certificate `a` is at least as good as `b` on the verdict and on the
///        bound: `a` ran, is certified when `b` is, and its lower bound is at least `b`'s.
bool atLeastAsGood(const plan::Certificate& a, const plan::Certificate& b);

/// \brief Certify `plan`, its candidates, and choose (file comment). Every number in the
///        summary is finite. `cancel`, when given and true, stops the current step and
///        the rest: the planner's plan is returned, certified if that had finished.
/// \throws InputError when the plan does not fit the refiner's cell.
RefinementResult refineAndCertify(const trajopt::PlanRefiner& refiner, const plan::Plan& plan,
                                  const plan::PlanMargins& margins,
                                  const plan::CertificateSettings& certificate,
                                  const std::atomic<bool>* cancel = nullptr);

}  // namespace rbsf::planner
