#pragma once
/// \file
/// \brief The certificate of a plan: evidence that it runs on a cell. N closed-loop trials
///        (trial.h), each with a plant drawn from the cell's uncertainty, the cell's sensors
///        and the control law (control_law.h), judged by outcome; certified when the share
///        of successes is at least required_rate.
///
/// The law is the one the cell's sensing allows: part feedback (TV-LQR with the part's
/// pose) when the cell senses the part, joint feedback (joint PD) when it does not, or
/// the plan's inputs alone (open_loop, for comparison). Whatever the trials, a plan is
/// certified only when it keeps the cell's motion limits (plan_motion.h) and, under the
/// joint law, when the joints alone fix the part along it but for stretches of at most
/// holding.max_free_time (plan_holding.h). Its gains are made once from the
/// cell as given (the controller knows the nominal cell, not the draw).
///
/// Reproducible: trial i draws from (seed, i) alone, so the certificate is the same bits
/// for a seed whatever the number of threads; trials run on every core (threads = 0).
/// The worst trial: a failed one before any success, a dropped one before any other
/// failure (the earliest drop first); among the rest alike, the largest
/// max(position error / tolerance, angle error / tolerance) at the end; then the lowest
/// index.

#include <atomic>
#include <cstdint>
#include <vector>

#include "rbsf/dynamics/feedback_schedule.h"
#include "rbsf/dynamics/model.h"
#include "rbsf/plan/certificate_report.h"
#include "rbsf/plan/plan.h"
#include "rbsf/plan/trial.h"

namespace rbsf::plan {

/// \brief How a certificate is made; defaults documented.
struct CertificateSettings {
  int trials = 32;              ///< N (>= 1)
  std::uint64_t seed = 1;       ///< of the draws
  double required_rate = 0.95;  ///< certified when successes / N >= this
  int threads = 0;              ///< 0: one per core
  bool open_loop = false;       ///< the plan's inputs alone instead of the law
  TrialSettings trial;          ///< criteria
  HoldingSettings holding;      ///< the plan's holding, judged under the joint law
  FeedbackSettings feedback;    ///< the law's gains (settle_time: the hold after the plan)
};

/// \brief The rules of CertificateSettings, in one place (certify() and the pipeline check
///        through it): trials in 1..100000, required_rate in [0, 1], threads >= 0, the
///        trial's tolerances, windows and limits positive, saturation_time >= 0, holding's
///        free time, touch force and slip rate >= 0. \throws InputError naming the setting.
void checkSettings(const CertificateSettings& settings);

/// \brief Run the trials and judge them.
/// \param model the cell the law is made for and the trials draw around (its sensing and
///        uncertainty too).
/// \param outcomes when given, receives every trial's outcome in index order.
/// \param cancel when set and it becomes true, the remaining trials are skipped and the
///        certificate is not certified (ran stays false).
/// \throws InputError for settings out of range or a plan that does not fit the cell.
Certificate certify(const RbsfModel& model, const Plan& plan, const CertificateSettings& settings,
                    std::vector<TrialOutcome>* outcomes = nullptr,
                    const std::atomic<bool>* cancel = nullptr);

/// \brief True when `a` is the better evidence: a certificate that ran before one that did
///        not, a certified one before one that is not, more successes, then the smaller
///        final error of the worst trial (max of position / tolerance and angle /
///        tolerance; a drop is the largest). Equal certificates: false.
bool betterCertificate(const Certificate& a, const Certificate& b);

/// \brief Trial `index` of a certificate again, with every step's true state in `trace`
///        (index -1: the nominal trial, no draws and no sensor noise).
TrialOutcome traceTrial(const RbsfModel& model, const Plan& plan,
                        const CertificateSettings& settings, int index,
                        std::vector<TrajectorySample>& trace);

}  // namespace rbsf::plan
