#pragma once
/// \file
/// \brief The certificate of a plan: evidence that it runs on a cell. Closed-loop trials
///        (trial.h), each with a plant drawn from the cell's uncertainty, the cell's sensors
///        and the control law (control_law.h), judged by outcome; certified when the
///        one-sided Clopper-Pearson lower bound of the success rate (confidence.h) at
///        `confidence` is at least required_rate. A share of successes alone is weak
///        evidence: a plan that succeeds 90 % of the time passes 32 of 32 trials 3.4 % of
///        the time, while 64 of 64 bound the rate at 0.954 with 95 % confidence.
///
/// How many trials: a fixed count (`trials` > 0) runs exactly that many and judges them by
/// the bound (fewer than 59 can never reach 0.95 at 95 % confidence). Sequential (`trials`
/// = 0, the default) runs them in batches of `batch` and looks at the bound after each
/// batch, never within one: certified as soon as the lower bound reaches required_rate;
/// not certified as soon as even successes in every remaining trial up to `max_trials`
/// could not bring it there (futility), or when the cap is reached; and not certified
/// after the first batch when the plan already fails the checks that do not depend on the
/// trials (motion limits, holding). A good plan stops at the first batch (64 of 64), a
/// hopeless one too (futility), and a plan near the line gets the trials it needs.
///
/// The error rate of a sequential certificate: each look at the bound errs with
/// probability at most 1 - confidence, but the certificate looks up to max_trials / batch
/// times and certifies at the first look that passes, so its overall chance of certifying
/// a plan whose true rate is just below required_rate is above 1 - confidence. With the
/// defaults (batches of 64 up to 512, 0.95 at 95 %), computed exactly over the binomial
/// outcomes of every look: a plan whose true rate is 0.95 is certified 12.8 % of the time
/// (a single look: at most 5 %), at 0.94 4.1 %, at 0.90 0.13 % (the former rule, 95 % of
/// 32 trials, certified a 90 % plan 16 % of the time); a plan at 0.99 is certified with
/// probability 0.999996 after 105 trials on average, one at 0.999 after 68. A fixed count
/// errs at most at the nominal rate, 1 - confidence.
///
/// The law is the one the cell's sensing allows: part feedback (TV-LQR with the part's
/// pose) when the cell senses the part, joint feedback (joint PD) when it does not, or
/// the plan's inputs alone (open_loop, for comparison). Whatever the trials, a plan is
/// certified only when it keeps the cell's motion limits (plan_motion.h) and, under the
/// joint law, when the joints alone fix the part along it but for stretches of at most
/// holding.max_free_time (plan_holding.h). Its gains are made once from the
/// cell as given (the controller knows the nominal cell, not the draw).
///
/// Reproducible: trial i draws from (seed, i) alone and decisions are taken at batch
/// boundaries only, on the trials before them, so the certificate is the same bits for a
/// seed whatever the number of threads; trials run on every core (threads = 0).
/// The worst trial: a failed one before any success, a dropped one before any other
/// failure (the earliest drop first); among the rest alike, the largest
/// max(position error / tolerance, angle error / tolerance) at the end; then the lowest
/// index.

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/plan/certificate_report.h"
#include "rbsf/plan/plan.h"
#include "rbsf/plan/trial.h"

namespace rbsf::plan {

/// \brief How a certificate is made; defaults documented.
struct CertificateSettings {
  int trials = 0;            ///< a fixed count of trials (1..100000); 0: sequential (file comment)
  int batch = 64;            ///< sequential: trials between two looks at the bound (>= 1)
  int max_trials = 512;      ///< sequential: the cap on trials (batch..100000)
  double confidence = 0.95;  ///< of the lower bound, in [0.5, 1)
  double required_rate = 0.95;  ///< certified when the lower bound of the rate is >= this
  std::uint64_t seed = 1;       ///< of the draws
  int threads = 0;              ///< 0: one per core
  bool open_loop = false;       ///< the plan's inputs alone instead of the law
  TrialSettings trial;          ///< criteria
  HoldingSettings holding;      ///< the plan's holding, judged under the joint law
  FeedbackSettings feedback;    ///< the law's gains (settle_time: the hold after the plan)
};

/// \brief The rules of CertificateSettings, in one place (certify() and the pipeline check
///        through it): trials in 0..100000, batch in 1..100000, max_trials in
///        batch..100000, confidence in [0.5, 1) (below 0.5 the "lower" bound lies above the
///        observed rate), required_rate in [0, 1], threads >= 0, the trial's tolerances,
///        windows and limits positive, saturation_time >= 0, holding's free time, touch force
///        and slip rate >= 0. \throws InputError naming the setting.
void checkSettings(const CertificateSettings& settings);

/// \brief Run the trials (a fixed count or sequentially, file comment) and judge them.
/// \param model the cell the law is made for and the trials draw around (its sensing and
///        uncertainty too).
/// \param outcomes when given, receives the outcome of every trial counted, in index order
///        (trials run past a sequential decision on other threads are not counted).
/// \param cancel when set and it becomes true, the remaining trials are skipped and the
///        certificate is not certified (ran stays false).
/// \throws InputError for settings out of range or a plan that does not fit the cell.
Certificate certify(const RbsfModel& model, const Plan& plan, const CertificateSettings& settings,
                    std::vector<TrialOutcome>* outcomes = nullptr,
                    const std::atomic<bool>* cancel = nullptr);

/// \brief The trials of a certificate and its rule for how many (file comment), over any
///        trial: certify() runs it with closed-loop trials; a test can run it on a given
///        sequence of outcomes. Runs trial(i) for i = 0, 1, ... on settings.threads threads
///        (0: one per core) and looks at the bound after each batch (or once, after a fixed
///        count).
/// \param plan_ok false when the plan fails the checks that do not depend on the trials: a
///        sequential run then stops at its first look.
/// \param trial called from any of the threads, for each index taken (including those
///        taken past a decision, which are not counted); its outcome's `success` counts.
/// \param outcomes receives the counted trials' outcomes in index order (index set).
/// \returns false when `cancel` became true before the decision (outcomes empty).
/// \throws InputError for settings out of range; rethrows the first exception of a trial.
bool runTrials(const CertificateSettings& settings, bool plan_ok,
               const std::function<TrialOutcome(int index)>& trial,
               std::vector<TrialOutcome>& outcomes, const std::atomic<bool>* cancel = nullptr);

/// \brief True when `a` is the better evidence: a certificate that ran before one that did
///        not, a certified one before one that is not, the higher lower bound of the success
///        rate, then the smaller final error of the worst trial (max of position / tolerance
///        and angle / tolerance; a drop is the largest). Equal certificates: false.
///
/// The lower bound, not the count of successes nor the observed rate, because sequential
/// certificates of different plans stop after different numbers of trials: 60 of 64 and
/// 118 of 128 are not comparable as counts, and 4 of 4 (rate 1, bound 0.47) is weaker
/// evidence than 120 of 128 (rate 0.94, bound 0.89). For certificates of one trial count
/// the bound grows with the successes, so the order is the old one. The bounds compare
/// evidence only when the certificates share a confidence level (one settings struct, as
/// in the pipeline and the refinement). Every plan with no success has the bound 0: the
/// worst trial's error decides between them.
bool betterCertificate(const Certificate& a, const Certificate& b);

/// \brief Trial `index` of a certificate again, with every step's true state in `trace`
///        (index -1: the nominal trial, no draws and no sensor noise).
TrialOutcome traceTrial(const RbsfModel& model, const Plan& plan,
                        const CertificateSettings& settings, int index,
                        std::vector<TrajectorySample>& trace);

}  // namespace rbsf::plan
