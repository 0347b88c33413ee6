#include "rbsf/planner/plan_replay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/state_layout.h"
#include "rbsf/planner/goal.h"
#include "rbsf/planner/plan_reference.h"

namespace rbsf::planner {

namespace {

char letter(Phase p) { return p == Phase::kC ? 'C' : p == Phase::kP ? 'P' : 'U'; }

}  // namespace

std::string filterPhaseRuns(const std::vector<std::pair<Phase, double>>& runs, double min_run) {
  // Merge equal neighbours first: a phase split over two segments is one run.
  std::vector<std::pair<char, double>> merged;
  for (const auto& [phase, d] : runs) {
    const char c = letter(phase);
    if (!merged.empty() && merged.back().first == c)
      merged.back().second += d;
    else
      merged.emplace_back(c, d);
  }
  std::string seq;
  for (const auto& [c, d] : merged)
    if (d >= min_run && (seq.empty() || seq.back() != c)) seq.push_back(c);
  if (seq.empty() && !merged.empty())
    seq.push_back(std::max_element(merged.begin(), merged.end(), [](auto& a, auto& b) {
                    return a.second < b.second;
                  })->first);
  return seq;
}

std::string plannedPhases(const Plan& plan, double min_run) {
  std::vector<std::pair<Phase, double>> runs;
  for (const PlanSegment& s : plan.segments) runs.emplace_back(s.phase, s.duration);
  return filterPhaseRuns(runs, min_run);
}

ReplayResult replayPlan(const Simulator& simulator, const Plan& plan,
                        const TrackingController* controller, const ReplaySettings& settings) {
  const RbsfModel& model = simulator.model();
  if (plan.q0.size() != model.configDim())
    throw InputError("plan's q0 does not fit the cell (" + std::to_string(plan.q0.size()) +
                     " coordinates for " + std::to_string(model.numFingers()) + " fingers)");
  const ReferenceTrajectory ref = makeReference(plan);
  const double h = simulator.settings().time_step;
  const long steps = std::lround(plan.duration() / h);
  const int m = model.numFingers();

  SimState state(plan.q0, VecQ::Zero(plan.q0.size()));
  SimulatorWorkspace ws(m);
  StepReport report;
  ReferenceSample at, mid;
  VecU tau;
  ReplayResult r;
  double min_fn = std::numeric_limits<double>::infinity();
  // Each segment is labelled by majorityPhase, as the planner labels its own segments, so a
  // plan's own open-loop replay reproduces its labels exactly (plannedPhases).
  std::vector<std::pair<Phase, double>> runs;
  PhaseCounts count{};  // of the current segment
  std::size_t segment = 0;
  double segment_end = plan.segments.front().duration;  // makeReference refused none
  auto closeSegment = [&] {  // a segment shorter than a step has no phase of its own
    if (count[0] + count[1] + count[2] == 0) return;
    runs.emplace_back(majorityPhase(count), plan.segments[segment].duration);
    count.fill(0);
  };
  // Where the part first leaves the plan's own path (by the acceptance tolerances): the
  // time and planned phase a user looks at to see which part of a plan is fragile.
  auto checkDeparture = [&](double t) {
    if (r.departure_time >= 0.0) return;
    const double dp =
        std::hypot(state.q[layout::kX] - at.q[layout::kX], state.q[layout::kY] - at.q[layout::kY]);
    const double da = std::abs(state.q[layout::kPhi] - at.q[layout::kPhi]);
    if (!(dp <= settings.position_tolerance) || !(da <= settings.angle_tolerance)) {
      r.departure_time = t;
      r.departure_phase = std::string(1, letter(plan.segments[segment].phase));
    }
  };
  for (long n = 0; n < steps; ++n) {
    const double t = static_cast<double>(n) * h;
    while (segment + 1 < plan.segments.size() && t + 0.5 * h >= segment_end) {
      closeSegment();
      segment_end += plan.segments[++segment].duration;
    }
    ref.sample(t, at);
    ref.sample(t + 0.5 * h, mid);
    checkDeparture(t);
    r.max_tracking_error =
        std::max(r.max_tracking_error, TrackingController::jointError(state.q, at));
    if (controller) {
      at.tau = mid.tau;
      controller->compute(state.q, state.v, at, tau);
    } else {
      tau = mid.tau;
    }
    simulator.step(state, tau, ws, &report);
    for (int i = 0; i < m; ++i)
      if (report.contacts[i].mode != ContactMode::kSeparated)
        min_fn = std::min(min_fn, report.contacts[i].f_n);
    const Phase ph = report.phase == Phase::kUnsupported ? Phase::kU : report.phase;
    ++count[static_cast<int>(ph)];
  }
  closeSegment();
  ref.sample(static_cast<double>(steps) * h, at);
  checkDeparture(static_cast<double>(steps) * h);
  r.max_tracking_error =
      std::max(r.max_tracking_error, TrackingController::jointError(state.q, at));
  r.position_error =
      std::hypot(state.q[layout::kX] - plan.goal.x, state.q[layout::kY] - plan.goal.y);
  // The goal angle the plan turns to: phi_g taken within pi of the plan's own final angle,
  // so "nearest" and "absolute" goals are both meant, and a replay that ends a whole turn
  // away from where the plan ends is an error of 2 pi, not 0.
  const double plan_phi = at.q[layout::kPhi];
  const double goal_phi = plan_phi + angleDifference(plan.goal.phi, plan_phi);
  r.angle_error = std::abs(state.q[layout::kPhi] - goal_phi);
  r.min_f_n = std::isfinite(min_fn) ? min_fn : 0.0;
  r.phases = filterPhaseRuns(runs, settings.min_phase_run);
  return r;
}

std::string departureText(const ReplayResult& result) {
  if (result.departure_time < 0.0) return "";
  char buf[96];
  std::snprintf(buf, sizeof buf, "leaves the planned path at t = %.3f s (planned phase %s)",
                result.departure_time, result.departure_phase.c_str());
  return buf;
}

namespace {

/// `seen` is `planned` and one settling run (file comment of plan_replay.h).
bool endsSettling(const Plan& plan, const std::string& seen, const std::string& planned,
                  double rest_speed) {
  if (planned.empty() || seen.size() != planned.size() + 1 ||
      seen.compare(0, planned.size(), planned) != 0 || plan.samples.empty())
    return false;
  const VecQ& v = plan.samples.back().v;
  for (int k = 0; k < layout::kObjectDim; ++k)
    if (!(std::abs(v[k]) <= rest_speed)) return false;
  const char last = planned.back(), extra = seen.back();
  return (last == 'U' && (extra == 'P' || extra == 'C')) || (last == 'P' && extra == 'C');
}

}  // namespace

bool acceptReplay(const Plan& plan, const ReplayResult& closed, const ReplaySettings& settings,
                  std::string* reason) {
  std::string why;
  char buf[160];
  if (!(closed.position_error <= settings.position_tolerance)) {
    std::snprintf(buf, sizeof buf, "final position error %.4g m > %.4g m; ", closed.position_error,
                  settings.position_tolerance);
    why += buf;
  }
  if (!(closed.angle_error <= settings.angle_tolerance)) {
    std::snprintf(buf, sizeof buf, "final angle error %.4g deg > %.4g deg; ",
                  closed.angle_error * 180 / M_PI, settings.angle_tolerance * 180 / M_PI);
    why += buf;
  }
  if (!(closed.min_f_n >= 0.0)) {
    std::snprintf(buf, sizeof buf, "min f_n %.4g N < 0; ", closed.min_f_n);
    why += buf;
  }
  const std::string planned = plannedPhases(plan, settings.min_phase_run);
  if (closed.phases != planned && !endsSettling(plan, closed.phases, planned, settings.rest_speed))
    why += "phases " + closed.phases + " != planned " + planned + "; ";
  if (!why.empty() && closed.departure_time >= 0.0) why += departureText(closed) + "; ";
  if (!why.empty()) why.resize(why.size() - 2);
  if (reason) *reason = "closed-loop replay: " + (why.empty() ? std::string("accepted") : why);
  return why.empty();
}

ReplaySummary verifyPlan(const Simulator& simulator, const Plan& plan,
                         const ReplaySettings& settings, std::string* reason) {
  const TrackingController controller(simulator.model(), plan.q0, settings.tracking);
  ReplaySummary summary;
  summary.closed_loop = replayPlan(simulator, plan, &controller, settings);
  summary.open_loop = replayPlan(simulator, plan, nullptr, settings);
  summary.ran = true;
  summary.accepted = acceptReplay(plan, summary.closed_loop, settings, reason);
  return summary;
}

}  // namespace rbsf::planner
