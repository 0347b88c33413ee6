#include "rbsf/plan/certificate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>
#include <tuple>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/plan/confidence.h"
#include "rbsf/plan/plan_reference.h"

namespace rbsf::plan {

namespace {

void checkFits(const RbsfModel& model, const Plan& plan, const CertificateSettings& s) {
  checkSettings(s);
  if (plan.q0.size() != model.configDim())
    throw InputError("the plan is for " + std::to_string(plan.q0.size() - 4) +
                     " fingers, the cell has " + std::to_string(model.numFingers()));
}

}  // namespace

void checkSettings(const CertificateSettings& s) {
  if (s.trials < 0 || s.trials > 100000)
    throw InputError("certificate: trials must be in 0..100000, 0 for sequential (got " +
                     std::to_string(s.trials) + ")");
  if (s.batch < 1 || s.batch > 100000)
    throw InputError("certificate: batch must be in 1..100000 (got " + std::to_string(s.batch) +
                     ")");
  if (s.max_trials < s.batch || s.max_trials > 100000)
    throw InputError("certificate: max_trials must be in batch..100000 (got " +
                     std::to_string(s.max_trials) + " with batch " + std::to_string(s.batch) + ")");
  if (!(s.confidence >= 0.5 && s.confidence < 1.0))
    throw InputError("certificate: confidence must be in [0.5, 1)");
  if (!(s.required_rate >= 0.0 && s.required_rate <= 1.0))
    throw InputError("certificate: required_rate must be in [0, 1]");
  if (s.threads < 0) throw InputError("certificate: threads must be >= 0");
  const TrialSettings& t = s.trial;
  for (double x : {t.position_tolerance, t.angle_tolerance, t.rest_window, t.drop_time,
                   t.lost_distance, t.min_phase_run})
    if (!(std::isfinite(x) && x > 0.0))
      throw InputError("certificate: tolerances, windows and limits must be positive");
  if (!(t.saturation_time >= 0.0)) throw InputError("certificate: saturation_time must be >= 0");
  const HoldingSettings& h = s.holding;
  if (!(h.max_free_time >= 0.0 && std::isfinite(h.max_free_time) && h.touch_force >= 0.0 &&
        h.slip_rate >= 0.0))
    throw InputError("certificate: holding's free time, touch force and slip rate must be >= 0");
}

namespace {

/// Badness of an outcome for the worst-trial choice: failures first, then the final error.
std::pair<int, double> badness(const TrialOutcome& o, const TrialSettings& s) {
  const double err =
      std::max(o.position_error / s.position_tolerance, o.angle_error / s.angle_tolerance);
  return {o.success ? 0 : 1, o.dropped ? std::numeric_limits<double>::infinity() : err};
}

FeedbackSchedule makeSchedule(const RbsfModel& model, const Plan& plan,
                              const CertificateSettings& s) {
  return FeedbackSchedule(model, makeReference(plan), lawSensing(model.cell().sensing, plan),
                          plan.simulator, s.feedback);
}

/// The plan fails the checks that do not depend on the trials.
bool planFails(const Certificate& c) {
  return !c.motion.ok() || (c.holding_required && !c.holding.ok());
}

}  // namespace

std::string ratesText(const Certificate& c) {
  const bool reached = c.lower_bound >= c.required_rate;
  // Rounded down, so that the comparison printed holds for the printed figure; more digits
  // when three would not show it.
  double shown = std::floor(c.lower_bound * 1000.0) / 1000.0;
  int digits = 3;
  if ((shown >= c.required_rate) != reached) {
    shown = std::floor(c.lower_bound * 1e6) / 1e6;
    digits = 6;
  }
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%d/%d trials succeeded (%d %%; %g %% lower confidence bound %.*f %s %g required)",
                c.successes, c.trials, c.trials > 0 ? 100 * c.successes / c.trials : 0,
                100.0 * c.confidence, digits, shown, reached ? ">=" : "<", c.required_rate);
  return buf;
}

std::string stopText(const Certificate& c) {
  if (!c.sequential) return "";
  char buf[256];
  int n = std::snprintf(buf, sizeof buf,
                        "sequential, batches of %d up to %d trials: stopped after %d, ", c.batch,
                        c.max_trials, c.trials);
  if (c.certified)
    std::snprintf(buf + n, sizeof buf - n, "the bound reached the required rate");
  else if (planFails(c))
    std::snprintf(buf + n, sizeof buf - n,
                  "the plan fails its motion limits or holding whatever the trials");
  else if (c.trials >= c.max_trials)
    std::snprintf(buf + n, sizeof buf - n, "the cap");
  else
    std::snprintf(buf + n, sizeof buf - n,
                  "even %d more successes would leave the bound below the required rate",
                  c.max_trials - c.trials);
  return buf;
}

const char* toString(TrialLaw law) {
  switch (law) {
    case TrialLaw::kPartFeedback:
      return "part feedback";
    case TrialLaw::kJointFeedback:
      return "joint feedback";
    case TrialLaw::kOpenLoop:
      return "open loop";
  }
  return "?";
}

TrialEnd trialEnd(const TrialOutcome& o) {
  if (o.dropped) return TrialEnd::kLost;
  if (o.hold != HoldReason::kNone) return TrialEnd::kHeld;
  return o.success ? TrialEnd::kDone : TrialEnd::kOff;
}

const char* toString(TrialEnd end) {
  switch (end) {
    case TrialEnd::kDone:
      return "done";
    case TrialEnd::kHeld:
      return "held";
    case TrialEnd::kLost:
      return "lost";
    case TrialEnd::kOff:
      return "off";
  }
  return "?";
}

TrialLaw parseTrialLaw(std::string_view name, const std::string& where) {
  for (TrialLaw law : {TrialLaw::kPartFeedback, TrialLaw::kJointFeedback, TrialLaw::kOpenLoop})
    if (name == toString(law)) return law;
  throw InputError(where + ": unknown law '" + std::string(name) +
                   "' (part feedback, joint feedback or open loop)");
}

std::string verdictText(const Certificate& c) {
  if (!c.ran) return "not certified: no trials ran";
  std::string text = (c.certified ? "certified: " : "NOT certified: ") + ratesText(c);
  if (c.worst.index >= 0 && !c.worst.success)
    text += "; worst trial " + std::to_string(c.worst.index) + ": " + c.worst.failure;
  if (!c.motion.ok()) text += "; the plan " + motionViolationText(c.motion);
  if (c.holding_required && !c.holding.ok())
    text += "; the joints alone do not hold the part (" + holdingText(c.holding) + ")";
  return text;
}

std::string worstTrialText(const Certificate& c) {
  const TrialOutcome& w = c.worst;
  if (w.index < 0) return "no trial";
  char buf[512];
  int n = std::snprintf(buf, sizeof buf, "trial %d: ", w.index);
  if (w.dropped)
    n += std::snprintf(buf + n, sizeof buf - n, "part dropped at t = %.3f s, ", w.dropped_time);
  n += std::snprintf(buf + n, sizeof buf - n,
                     "ends %.3g m and %.3g deg from the goal, moving %.3g m/s and %.3g deg/s",
                     w.position_error, w.angle_error * 180 / M_PI, w.speed,
                     w.angular_speed * 180 / M_PI);
  if (w.departure_time >= 0.0)
    n += std::snprintf(buf + n, sizeof buf - n,
                       "; left the planned path at t = %.3f s (planned phase %s)", w.departure_time,
                       w.departure_phase.c_str());
  std::snprintf(buf + n, sizeof buf - n, "; phases %s", w.phases.c_str());
  return buf;
}

std::string certificateReportText(const Certificate& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "certificate (%s, %d trials, seed %llu): %s\n", toString(c.law),
                c.trials, static_cast<unsigned long long>(c.seed),
                c.certified ? "CERTIFIED" : "NOT CERTIFIED");
  std::string text = buf;
  text += "  " + ratesText(c) + "\n";
  if (c.sequential) text += "  " + stopText(c) + "\n";
  text += "  worst " + worstTrialText(c) + "\n";
  if (c.worst.index >= 0 && !c.worst.success) text += "  it failed: " + c.worst.failure + "\n";
  text += "  " + motionText(c.motion) + "\n";
  if (c.holding_required) text += "  " + holdingText(c.holding) + "\n";
  return text;
}

bool betterCertificate(const Certificate& a, const Certificate& b) {
  auto rank = [](const Certificate& c) {
    const TrialOutcome& w = c.worst;
    const double error =
        w.dropped || w.index < 0
            ? std::numeric_limits<double>::infinity()
            : std::max(w.position_error / c.position_tolerance, w.angle_error / c.angle_tolerance);
    return std::make_tuple(c.ran, c.certified, c.lower_bound, -error);
  };
  return rank(a) > rank(b);
}

namespace {

/// The trial counts at which the bound is looked at: once at a fixed count; else after
/// every batch, the last look at the cap.
std::vector<int> lookCounts(const CertificateSettings& s) {
  if (s.trials > 0) return {s.trials};
  std::vector<int> out;
  for (int n = s.batch; out.empty() || out.back() < s.max_trials; n += s.batch)
    out.push_back(std::min(n, s.max_trials));
  return out;
}

/// Whether the look after `n` trials with `successes` ends the certificate (file comment
/// of certificate.h): a fixed count's one look, a plan that fails whatever the trials, the
/// bound reached, the cap, or futility.
bool decided(const CertificateSettings& s, int successes, int n, bool plan_ok) {
  if (s.trials > 0 || !plan_ok || n >= s.max_trials) return true;
  if (clopperPearsonLower(successes, n, s.confidence) >= s.required_rate) return true;
  const int left = s.max_trials - n;
  return clopperPearsonLower(successes + left, s.max_trials, s.confidence) < s.required_rate;
}

}  // namespace

bool runTrials(const CertificateSettings& s, bool plan_ok,
               const std::function<TrialOutcome(int index)>& trial,
               std::vector<TrialOutcome>& counted_outcomes, const std::atomic<bool>* cancel) {
  checkSettings(s);
  counted_outcomes.clear();
  // Workers take trial indices in order until the certificate is decided; whoever completes
  // the last trial of a batch judges it, and the batches in order, so decisions see only
  // whole batches before them: the same bits whatever the threads. Trials taken past a
  // decision still run (at most one per other thread) and are not counted.
  const std::vector<int> looks = lookCounts(s);
  const int most = looks.back();
  std::vector<TrialOutcome> outcomes(static_cast<std::size_t>(most));
  std::vector<int> left_in_look(looks.size());
  for (std::size_t k = 0; k < looks.size(); ++k)
    left_in_look[k] = looks[k] - (k == 0 ? 0 : looks[k - 1]);
  auto lookOf = [&](int i) {
    return s.trials > 0 ? 0 : std::min(i / s.batch, static_cast<int>(looks.size()) - 1);
  };
  std::atomic<int> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;  // guards what follows, and the outcomes of trials being judged
  std::exception_ptr error;
  std::size_t judged = 0;
  int successes = 0, counted = 0;
  auto judge = [&] {
    while (counted == 0 && judged < looks.size() && left_in_look[judged] == 0) {
      const int from = judged == 0 ? 0 : looks[judged - 1], to = looks[judged];
      for (int i = from; i < to; ++i) successes += outcomes[static_cast<std::size_t>(i)].success;
      ++judged;
      if (decided(s, successes, to, plan_ok)) {
        counted = to;
        stop = true;
      }
    }
  };
  auto worker = [&] {
    while (!stop && !(cancel && cancel->load())) {
      const int i = next++;
      if (i >= most) return;
      try {
        TrialOutcome o = trial(i);
        o.index = i;
        const std::lock_guard<std::mutex> lock(mutex);
        outcomes[static_cast<std::size_t>(i)] = std::move(o);
        --left_in_look[static_cast<std::size_t>(lookOf(i))];
        judge();
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
    }
  };
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::min(most, s.threads > 0 ? s.threads : cores);
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (counted == 0) return false;  // cancelled before the decision
  outcomes.resize(static_cast<std::size_t>(counted));
  counted_outcomes = std::move(outcomes);
  return true;
}

Certificate certify(const RbsfModel& model, const Plan& plan, const CertificateSettings& s,
                    std::vector<TrialOutcome>* all, const std::atomic<bool>* cancel) {
  checkFits(model, plan, s);
  const FeedbackSchedule schedule = makeSchedule(model, plan, s);
  Certificate c;
  c.law = s.open_loop               ? TrialLaw::kOpenLoop
          : schedule.partFeedback() ? TrialLaw::kPartFeedback
                                    : TrialLaw::kJointFeedback;
  c.confidence = s.confidence;
  c.required_rate = s.required_rate;
  c.sequential = s.trials == 0;
  c.batch = c.sequential ? s.batch : 0;
  c.max_trials = c.sequential ? s.max_trials : 0;
  c.seed = s.seed;
  c.settle_time = s.feedback.timing.settle_time;
  c.position_tolerance = s.trial.position_tolerance;
  c.angle_tolerance = s.trial.angle_tolerance;
  c.rest_speed = model.cell().motion_limits.rest_speed;
  c.rest_angular_speed = model.cell().motion_limits.rest_angular_speed;
  c.sensing = model.cell().sensing;
  c.uncertainty = model.cell().uncertainty;
  // The checks that do not depend on the trials come first: a sequential certificate of a
  // plan that fails them stops at its first look.
  c.motion = measureMotion(plan, model.cell().motion_limits);
  c.holding_required = !s.open_loop && !schedule.partFeedback();
  if (c.holding_required) c.holding = measureHolding(model, plan, s.holding);
  const bool plan_ok = !planFails(c);

  std::vector<TrialOutcome> outcomes;
  const bool done = runTrials(
      s, plan_ok,
      [&](int i) {
        return runTrial(schedule, plan, drawTrial(model.cell(), plan, s.seed, i), s.trial,
                        s.open_loop);
      },
      outcomes, cancel);
  if (!done || (cancel && cancel->load())) return c;

  c.ran = true;
  for (const TrialOutcome& o : outcomes) {
    c.successes += o.success ? 1 : 0;
    if (c.worst.index < 0 || badness(o, s.trial) > badness(c.worst, s.trial)) c.worst = o;
  }
  c.trials = static_cast<int>(outcomes.size());
  c.success_rate = static_cast<double>(c.successes) / c.trials;
  c.lower_bound = clopperPearsonLower(c.successes, c.trials, s.confidence);
  c.certified = c.lower_bound >= s.required_rate && plan_ok;
  if (all) *all = std::move(outcomes);
  return c;
}

TrialOutcome traceTrial(const RbsfModel& model, const Plan& plan, const CertificateSettings& s,
                        int index, std::vector<TrajectorySample>& trace) {
  checkFits(model, plan, s);
  const FeedbackSchedule schedule = makeSchedule(model, plan, s);
  const TrialDraw draw =
      index < 0 ? nominalDraw(model.cell(), plan) : drawTrial(model.cell(), plan, s.seed, index);
  trace.clear();
  TrialOutcome o = runTrial(schedule, plan, draw, s.trial, s.open_loop, &trace);
  o.index = index;
  return o;
}

}  // namespace rbsf::plan
