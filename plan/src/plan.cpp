#include "rbsf/plan/plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/io/atomic_file.h"

namespace rbsf::plan {

namespace {

char phaseLetter(Phase p) { return p == Phase::kC ? 'C' : p == Phase::kP ? 'P' : 'U'; }

}  // namespace

double Plan::duration() const {
  double d = 0.0;
  for (const PlanSegment& s : segments) d += s.duration;
  return d;
}

std::string Plan::phaseSequence() const {
  std::string seq;
  for (const PlanSegment& s : segments) {
    const char c = std::string(toString(s.phase))[0];
    if (seq.empty() || seq.back() != c) seq.push_back(c);
  }
  return seq;
}

std::string Plan::plannedPhases() const {
  std::string seq;
  for (const PlanSegment& s : segments) {
    int sliders = 0, sticking = 0;
    for (const ContactRole r : s.contacts) {
      sliders += slipSign(r) != 0 ? 1 : 0;
      sticking += r == ContactRole::kStick ? 1 : 0;
    }
    const char c = sliders == 0 ? 'C' : sticking == 1 ? 'P' : sticking == 0 ? 'U' : 'C';
    if (seq.empty() || seq.back() != c) seq.push_back(c);
  }
  return seq;
}

int Plan::pivots() const {
  const std::string seq = plannedPhases();
  return static_cast<int>(std::count(seq.begin(), seq.end(), 'P'));
}

std::string filterPhaseRuns(const std::vector<std::pair<Phase, double>>& runs, double min_run) {
  // Merge equal neighbours first: a phase split over two segments is one run.
  std::vector<std::pair<char, double>> merged;
  for (const auto& [phase, d] : runs) {
    const char c = phaseLetter(phase);
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

std::string_view toString(PlanStatus status) {
  return status == PlanStatus::kExact ? "exact" : "approximate";
}

Phase parsePhase(const std::string& text) {
  if (text == "C") return Phase::kC;
  if (text == "P") return Phase::kP;
  if (text == "U") return Phase::kU;
  throw InputError("phase must be \"C\", \"P\" or \"U\" (got \"" + text + "\")");
}

Phase majorityPhase(const PhaseCounts& steps) {
  int best = 0;
  for (int p = 1; p < 3; ++p)
    if (steps[p] > steps[best]) best = p;
  return static_cast<Phase>(best);
}

std::vector<PlanSample> simulateSegments(const Simulator& simulator, const VecQ& q0,
                                         std::vector<PlanSegment>& segments, int sample_steps,
                                         std::vector<SimState>* ends, double min_force) {
  const int m = simulator.model().numFingers();
  const SimState start(q0, VecQ::Zero(q0.size()));
  SimState state = start;
  SimulatorWorkspace ws(m);
  std::vector<PlanSample> samples;
  auto record = [&](const SimState& at, const VecU& tau, const StepReport& report, Phase phase) {
    samples.push_back(trajectorySample(at, report, tau));
    samples.back().phase = phase;
  };
  std::vector<long> steps;
  std::vector<VecU> taus;
  for (const PlanSegment& seg : segments) {
    steps.push_back(seg.steps);
    taus.push_back(seg.tau);
  }
  HeldInputs inputs(steps, taus);
  PhaseCounts count{};
  RoleCounts roles{};
  rollout(simulator, state, inputs.totalSteps(), ws, inputs,
          [&](const SimState& now, const StepReport& report, const VecU& tau, long n) {
            const Phase ph = report.phase == Phase::kUnsupported ? Phase::kU : report.phase;
            ++count[static_cast<int>(ph)];
            for (int i = 0; i < m; ++i)
              ++roles[i][static_cast<int>(roleOf(report.contacts[i], min_force))];
            // t = 0: the start at rest, with the first step's tau, forces and phase.
            if (n == 0) record(start, tau, report, ph);
            const bool end = inputs.endsSegment(n);
            if ((n + 1) % sample_steps == 0 || end) record(now, tau, report, ph);
            if (end) {
              PlanSegment& seg = segments[inputs.segment()];
              seg.phase = majorityPhase(count);
              if (!planned(seg.contacts)) seg.contacts = majorityRoles(roles, m);
              count.fill(0);
              roles = RoleCounts{};
              if (ends) ends->push_back(now);
            }
            return true;
          });
  return samples;
}

void writePlanCsv(const Plan& plan, const std::string& path) {
  writeFileAtomically(path, planCsvText(plan), "plan CSV");
}

std::string planCsvText(const Plan& plan) {
  if (plan.q0.size() == 0) throw std::runtime_error("empty plan");
  return trajectoryCsvText(plan.samples, static_cast<int>(plan.q0.size()) - 4);
}

PlanCell planCell(const Cell& cell) {
  PlanCell c;
  c.recorded = true;
  for (const FingerParams& f : cell.fingers) c.finger_r.push_back(f.r);
  c.part_mass = cell.object.mass;
  c.part_inertia = cell.object.inertia;
  c.gravity = cell.gravity;
  c.friction_recorded = true;
  c.mu_static = cell.friction.mu_static;
  c.mu_kinetic = cell.friction.mu_kinetic;
  return c;
}

}  // namespace rbsf::plan
