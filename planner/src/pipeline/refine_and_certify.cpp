#include "rbsf/planner/pipeline/refine_and_certify.h"

#include <sstream>
#include <utility>
#include <vector>

namespace rbsf::planner {

namespace {

/// Why candidate `c` was not chosen, for the summary's message.
std::string whyNot(const trajopt::RefinementCandidate& c, const plan::Certificate& certificate,
                   bool none_chosen, const plan::Certificate& planners) {
  if (!c.usable) return c.reason;
  if (!certificate.ran) return "not certified (cancelled)";
  return "its certificate is " +
         (none_chosen ? std::string("short of the planner's plan's (") +
                            (planners.certified ? "certified, " : "") + "lower bound " +
                            std::to_string(planners.lower_bound) + ")"
                      : std::string("not better than the chosen one's")) +
         ": " + plan::verdictText(certificate);
}

}  // namespace

bool atLeastAsGood(const plan::Certificate& a, const plan::Certificate& b) {
  return a.ran && (a.certified || !b.certified) && a.lower_bound >= b.lower_bound;
}

RefinementResult refineAndCertify(const trajopt::PlanRefiner& refiner, const plan::Plan& plan,
                                  const plan::PlanMargins& margins,
                                  const plan::CertificateSettings& settings,
                                  const std::atomic<bool>* cancel) {
  const RbsfModel& model = refiner.model();
  auto cancelled = [cancel] { return cancel != nullptr && cancel->load(); };
  RefinementResult out;
  out.record.plan = plan;
  out.planner_certificate = plan::certify(model, plan, settings, nullptr, cancel);
  out.record.certificate = out.planner_certificate;

  std::vector<trajopt::RefinementCandidate> candidates;
  std::vector<plan::Certificate> certificates;
  const int offered = refiner.candidates(margins);
  for (int k = 0; k < offered && !cancelled(); ++k) {
    if (k > 0 && certificates.back().certified) break;
    candidates.push_back(refiner.candidate(plan, margins, k, cancel));
    certificates.emplace_back();
    trajopt::RefinementCandidate& c = candidates.back();
    if (c.usable && !cancelled()) {
      certificates.back() = plan::certify(model, c.plan, settings, nullptr, cancel);
      c.summary.refined_success_rate = certificates.back().success_rate;
    }
  }
  out.solves = static_cast<int>(candidates.size());
  if (candidates.empty()) return out;

  // The better refinement, then against the planner's plan (file comment).
  int best = -1;
  for (int k = 0; k < out.solves; ++k) {
    if (!certificates[k].ran) continue;
    if (best < 0 || plan::betterCertificate(certificates[k], certificates[best])) best = k;
  }
  if (best >= 0 && !atLeastAsGood(certificates[best], out.planner_certificate)) best = -1;
  std::ostringstream why;
  for (int k = 0; k < out.solves; ++k)
    if (k != best)
      why << (why.tellp() > 0 ? "; " : "") << candidates[k].label << ": "
          << whyNot(candidates[k], certificates[k], best < 0, out.planner_certificate);
  const int summary = best < 0 ? 0 : best;
  if (best >= 0) {
    out.record.plan = std::move(candidates[best].plan);
    out.record.certificate = certificates[best];
    out.refined = true;
  } else {
    out.reason = why.str();
  }
  out.record.optimization = candidates[summary].summary;
  out.converged = candidates[summary].converged;
  out.record.optimization.chosen = out.refined;
  out.record.optimization.message = why.str();
  return out;
}

}  // namespace rbsf::planner
