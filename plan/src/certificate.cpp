#include "rbsf/plan/certificate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <tuple>

#include "rbsf/dynamics/errors.h"
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
  if (s.trials < 1 || s.trials > 100000)
    throw InputError("certificate: trials must be in 1..100000 (got " + std::to_string(s.trials) +
                     ")");
  if (!(s.required_rate >= 0.0 && s.required_rate <= 1.0))
    throw InputError("certificate: required_rate must be in [0, 1]");
  if (s.threads < 0) throw InputError("certificate: threads must be >= 0");
  const TrialSettings& t = s.trial;
  for (double x : {t.position_tolerance, t.angle_tolerance, t.rest_window, t.rest_speed,
                   t.rest_angular_speed, t.drop_time, t.lost_distance, t.min_phase_run})
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

}  // namespace

std::string verdictText(const Certificate& c) {
  if (!c.ran) return "not certified: no trials ran";
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s: %d/%d trials succeeded (%.0f %%, %.0f %% required)",
                c.certified ? "certified" : "NOT certified", c.successes, c.trials,
                100.0 * c.success_rate, 100.0 * c.required_rate);
  std::string text = buf;
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
  std::snprintf(buf, sizeof buf, "certificate (%s, %d trials, seed %llu): %s\n", c.law.c_str(),
                c.trials, static_cast<unsigned long long>(c.seed),
                c.certified ? "CERTIFIED" : "NOT CERTIFIED");
  std::string text = buf;
  std::snprintf(buf, sizeof buf, "  %d/%d trials succeeded (%.0f %%, %.0f %% required)\n",
                c.successes, c.trials, 100.0 * c.success_rate, 100.0 * c.required_rate);
  text += buf;
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
    return std::make_tuple(c.ran, c.certified, c.successes, -error);
  };
  return rank(a) > rank(b);
}

Certificate certify(const RbsfModel& model, const Plan& plan, const CertificateSettings& s,
                    std::vector<TrialOutcome>* all, const std::atomic<bool>* cancel) {
  checkFits(model, plan, s);
  const FeedbackSchedule schedule = makeSchedule(model, plan, s);
  std::vector<TrialOutcome> outcomes(static_cast<std::size_t>(s.trials));
  std::atomic<int> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  auto worker = [&] {
    for (;;) {
      const int i = next++;
      if (i >= s.trials || (cancel && cancel->load())) return;
      try {
        const TrialDraw draw = drawTrial(model.cell(), plan, s.seed, i);
        outcomes[static_cast<std::size_t>(i)] =
            runTrial(schedule, plan, draw, s.trial, s.open_loop);
        outcomes[static_cast<std::size_t>(i)].index = i;
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = s.trials;
      }
    }
  };
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::min(s.trials, s.threads > 0 ? s.threads : cores);
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);

  Certificate c;
  c.law = s.open_loop ? "open loop" : schedule.partFeedback() ? "part feedback" : "joint feedback";
  c.trials = s.trials;
  c.required_rate = s.required_rate;
  c.seed = s.seed;
  c.settle_time = s.feedback.settle_time;
  c.position_tolerance = s.trial.position_tolerance;
  c.angle_tolerance = s.trial.angle_tolerance;
  c.rest_speed = s.trial.rest_speed;
  c.rest_angular_speed = s.trial.rest_angular_speed;
  c.sensing = model.cell().sensing;
  c.uncertainty = model.cell().uncertainty;
  if (cancel && cancel->load()) return c;
  c.ran = true;
  for (const TrialOutcome& o : outcomes) {
    c.successes += o.success ? 1 : 0;
    if (c.worst.index < 0 || badness(o, s.trial) > badness(c.worst, s.trial)) c.worst = o;
  }
  c.success_rate = static_cast<double>(c.successes) / c.trials;
  c.motion = measureMotion(plan, model.cell().motion_limits);
  c.holding_required = !s.open_loop && !schedule.partFeedback();
  if (c.holding_required) c.holding = measureHolding(model, plan, s.holding);
  c.certified =
      c.success_rate >= s.required_rate && c.motion.ok() && (!c.holding_required || c.holding.ok());
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
