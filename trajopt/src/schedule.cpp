#include "rbsf/trajopt/schedule.h"

#include "rbsf/dynamics/core/rollout.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace rbsf::trajopt {

namespace {

int strength(ContactRole r) { return static_cast<int>(r); }

// Wrapped difference b - a in (-pi, pi].
double wrappedDelta(double a, double b) { return std::remainder(b - a, 2.0 * M_PI); }

// The run's roles as the plan states them: S sticks; + and - slide the way the
// re-simulation slid (its sign agrees with the role's on the plans the support planner
// writes; the simulated foot points are what the collocation's xi continue); F sticks
// but is not relied on (no normal floor: the plant holds such a light touch by friction,
// and the part on two frictionless tips would not balance); L is off. The letter: C for two or more
// sticking, P for one, U for none.
void statedRoles(int m, const VecC& xi_start, const VecC& xi_end, PhaseRun& run) {
  int sticking = 0;
  for (int i = 0; i < m; ++i) {
    const rbsf::ContactRole r = run.planned[i];
    const double d = wrappedDelta(xi_start[i], xi_end[i]);
    run.role[i] = r == rbsf::ContactRole::kLifted ? ContactRole::kOff
                  : slipSign(r) != 0              ? ContactRole::kSlide
                                                  : ContactRole::kStick;
    run.relied[i] = r == rbsf::ContactRole::kStick || slipSign(r) != 0;
    const int sign = slipSign(r) == 0 ? 0 : (d > 1e-6 ? 1 : (d < -1e-6 ? -1 : 0));
    run.slide_direction[i] = sign;
    run.slide_rate[i] = sign == 0 ? 0.0 : std::abs(d) / run.duration;
    sticking += run.role[i] == ContactRole::kStick;
  }
  run.phase = sticking >= 2 ? Phase::kC : (sticking == 1 ? Phase::kP : Phase::kU);
}

}  // namespace

ContactRole Schedule::knotRole(int knot, int i) const {
  ContactRole r = ContactRole::kOff;
  if (knot > 0) r = role(knot - 1, i);
  if (knot < intervals() && strength(role(knot, i)) > strength(r)) r = role(knot, i);
  return r;
}

bool buildSchedule(const RbsfModel& model, const plan::Plan& plan, int intervals, RunCut cut,
                   Schedule& schedule, std::string& why) {
  const bool split_by_contact_modes = cut == RunCut::kContactModes;
  const int m = model.numFingers();
  schedule = Schedule{};
  if (plan.segments.empty()) {
    why = "the plan has no segments";
    return false;
  }
  for (const plan::PlanSegment& seg : plan.segments)
    if (seg.steps < 1) {
      why = "a segment of the plan holds no simulator step";
      return false;
    }
  const Simulator sim(model, plan.simulator);
  SimulatorWorkspace ws(m);
  SimState state(plan.q0, VecQ::Zero(plan.q0.size()));
  ModelData data(m);
  SimulatedSteps& steps = schedule.steps;
  steps.t.push_back(0.0);
  steps.q.push_back(state.q);
  steps.v.push_back(state.v);

  // One pass of the simulator: every step's state and contacts, each segment's mode counts
  // [contact][mode] and the foot points at its end (xi_at[s + 1]; xi_at[0] at the start).
  using Counts = std::array<std::array<int, 3>, kMaxFingers>;
  const int S = static_cast<int>(plan.segments.size());
  std::vector<Counts> seg_counts(S);
  std::vector<VecC> xi_at;
  model.updateContacts(state.q, data);
  xi_at.push_back(data.xi_hint);
  std::vector<long> seg_steps;
  std::vector<VecU> seg_tau;
  for (const plan::PlanSegment& seg : plan.segments) {
    seg_steps.push_back(seg.steps);
    seg_tau.push_back(seg.tau);
  }
  for (auto& c : seg_counts)
    for (auto& ci : c) ci.fill(0);
  HeldInputs inputs(seg_steps, seg_tau);
  rollout(sim, state, inputs.totalSteps(), ws, inputs,
          [&](const SimState& now, const StepReport& report, const VecU&, long n) {
            const std::size_t s = inputs.segment();
            const plan::PlanSegment& seg = plan.segments[s];
            for (int i = 0; i < m; ++i)
              ++seg_counts[s][i][static_cast<int>(report.contacts[i].mode)];
            steps.contacts.push_back(report.contacts);
            steps.t.push_back(steps.t.back() + seg.duration / std::max(1, seg.steps));
            steps.q.push_back(now.q);
            steps.v.push_back(now.v);
            if (inputs.endsSegment(n)) {
              model.updateContacts(now.q, data);
              xi_at.push_back(data.xi_hint);
            }
            return true;
          });
  // The mode a contact held for most of a segment.
  auto segmentModes = [&](int s) {
    std::array<int, kMaxFingers> key{};
    for (int i = 0; i < m; ++i) {
      const auto& c = seg_counts[s][i];
      key[i] = static_cast<int>(std::max_element(c.begin(), c.end()) - c.begin());
    }
    return key;
  };
  // Runs: maximal sequences of segments with one phase letter and, when split, one
  // segment mode per contact.
  // A plan that states its contacts' roles (support plans) is cut where they change: the
  // roles are what the planner meant, the simulated letters flicker at hand-overs.
  const bool stated = cut == RunCut::kStatedRoles;
  if (stated && !std::all_of(plan.segments.begin(), plan.segments.end(),
                             [](const plan::PlanSegment& g) { return planned(g.contacts); })) {
    why = "the plan does not state every segment's contact roles";
    return false;
  }
  auto groupRuns = [&](bool split, std::vector<int>& first_segment) {
    first_segment.clear();
    first_segment.push_back(0);
    for (int s = 1; s < S; ++s) {
      const bool cut = stated ? plan.segments[s].contacts != plan.segments[s - 1].contacts
                              : plan.segments[s].phase != plan.segments[s - 1].phase ||
                                    (split && segmentModes(s) != segmentModes(s - 1));
      if (cut) first_segment.push_back(s);
    }
    first_segment.push_back(S);
  };
  std::vector<int> first_segment;
  groupRuns(split_by_contact_modes, first_segment);
  if (!stated && split_by_contact_modes &&
      intervals < 2 * (static_cast<int>(first_segment.size()) - 1))
    groupRuns(false, first_segment);  // too few intervals for the finer runs

  std::vector<Counts> counts;
  std::vector<VecC> xi_start, xi_end;
  double t = 0.0;
  for (std::size_t j = 0; j + 1 < first_segment.size(); ++j) {
    PhaseRun run;
    run.phase = plan.segments[first_segment[j]].phase;
    run.start = t;
    Counts c{};
    for (auto& ci : c) ci.fill(0);
    for (int s = first_segment[j]; s < first_segment[j + 1]; ++s) {
      run.duration += plan.segments[s].duration;
      for (int i = 0; i < m; ++i)
        for (int mode = 0; mode < 3; ++mode) c[i][mode] += seg_counts[s][i][mode];
    }
    t += run.duration;
    if (stated) run.planned = plan.segments[first_segment[j]].contacts;
    schedule.runs.push_back(run);
    counts.push_back(c);
    xi_start.push_back(xi_at[first_segment[j]]);
    xi_end.push_back(xi_at[first_segment[j + 1]]);
  }

  const int R = static_cast<int>(schedule.runs.size());
  for (int j = 0; j < R; ++j) {
    PhaseRun& run = schedule.runs[j];
    if (stated) {
      statedRoles(m, xi_start[j], xi_end[j], run);
      continue;
    }
    const auto& cnt = counts[j];
    auto stickCount = [&](int i) { return cnt[i][static_cast<int>(ContactMode::kStick)]; };
    for (int i = 0; i < m; ++i) {
      const int st = cnt[i][static_cast<int>(ContactMode::kStick)];
      const int sl = cnt[i][static_cast<int>(ContactMode::kSlide)];
      const int off = cnt[i][static_cast<int>(ContactMode::kSeparated)];
      run.role[i] = (off >= st + sl) ? ContactRole::kOff
                                     : (st >= sl ? ContactRole::kStick : ContactRole::kSlide);
      const double d = wrappedDelta(xi_start[j][i], xi_end[j][i]);
      run.slide_direction[i] = d > 1e-6 ? 1 : (d < -1e-6 ? -1 : 0);
      run.slide_rate[i] = std::abs(d) / run.duration;
    }
    // Contacts ordered by how often they stuck.
    std::array<int, kMaxFingers> order{};
    std::iota(order.begin(), order.begin() + m, 0);
    std::stable_sort(order.begin(), order.begin() + m,
                     [&](int a, int b) { return stickCount(a) > stickCount(b); });
    if (run.phase == Phase::kU) {
      for (int i = 0; i < m; ++i)
        if (run.role[i] == ContactRole::kStick) run.role[i] = ContactRole::kSlide;
    } else if (run.phase == Phase::kP) {
      for (int i = 0; i < m; ++i)
        if (run.role[i] == ContactRole::kStick) run.role[i] = ContactRole::kSlide;
      run.role[order[0]] = ContactRole::kStick;
    } else {
      int sticking = 0;
      for (int i = 0; i < m; ++i) sticking += run.role[i] == ContactRole::kStick;
      for (int r = 0; r < m && sticking < 2; ++r)
        if (run.role[order[r]] != ContactRole::kStick) {
          run.role[order[r]] = ContactRole::kStick;
          ++sticking;
        }
    }
    for (int i = 0; i < m; ++i) {
      run.relied[i] = run.role[i] != ContactRole::kOff;
      if (run.role[i] != ContactRole::kSlide) {
        run.slide_direction[i] = 0;
        run.slide_rate[i] = 0.0;
      }
    }
  }

  if (intervals < 2 * R) {
    why = "settings.knots = " + std::to_string(intervals) + " is fewer than 2 per phase run (" +
          std::to_string(R) + " runs)";
    return false;
  }
  // 2 per run, the rest in proportion to duration (largest remainder).
  const double total = plan.duration();
  const int spare = intervals - 2 * R;
  std::vector<double> share(R), frac(R);
  int given = 0;
  for (int j = 0; j < R; ++j) {
    share[j] = spare * schedule.runs[j].duration / total;
    schedule.runs[j].intervals = 2 + static_cast<int>(std::floor(share[j]));
    frac[j] = share[j] - std::floor(share[j]);
    given += schedule.runs[j].intervals;
  }
  std::vector<int> idx(R);
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) { return frac[a] > frac[b]; });
  for (int r = 0; given < intervals; ++r, ++given) ++schedule.runs[idx[r % R]].intervals;
  int first = 0;
  for (int j = 0; j < R; ++j) {
    schedule.runs[j].first_interval = first;
    for (int k = 0; k < schedule.runs[j].intervals; ++k) schedule.run_of_interval.push_back(j);
    first += schedule.runs[j].intervals;
  }
  return true;
}

}  // namespace rbsf::trajopt
