#include "rbsf/trajopt/schedule.h"

#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/state_layout.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace rbsf::trajopt {

namespace {

/// A run rests while the part moves at most this many times the cell's rest: a support
/// plan's closed-loop run settles into its end rest at up to 5 mrad/s for 0.1 s (the -45
/// degree plan), while its pivots and base turns move at 0.05 rad/s and more.
constexpr double kSettling = 10.0;

int strength(ContactRole r) { return static_cast<int>(r); }

// Wrapped difference b - a in (-pi, pi].
double wrappedDelta(double a, double b) { return std::remainder(b - a, 2.0 * M_PI); }

/// Mode counts of a segment or a run: [contact][ContactMode].
using ModeCounts = std::array<std::array<int, 3>, kMaxFingers>;

// The run's roles as the plan states them: S sticks; + and - slide the way the
// re-simulation slid (its sign agrees with the role's on the plans the support planner
// writes; the simulated foot points are what the collocation's xi continue); F sticks
// but is not relied on (no normal floor: the plant holds such a light touch by friction,
// and the part on two frictionless tips would not balance), unless it is apart for most of
// the run in the re-simulation (a finger still rising to join the part: the law reaches for
// it past its planned stroke), then off; L is off. The letter: C for two or more sticking, P
// for one, U for none.
void statedRoles(int m, const ModeCounts& cnt, const VecC& xi_start, const VecC& xi_end,
                 PhaseRun& run) {
  int sticking = 0;
  for (int i = 0; i < m; ++i) {
    const rbsf::ContactRole r = run.planned[i];
    const double d = wrappedDelta(xi_start[i], xi_end[i]);
    const int apart = cnt[i][static_cast<int>(ContactMode::kSeparated)];
    const bool rising =
        r == rbsf::ContactRole::kFree && 2 * apart > cnt[i][0] + cnt[i][1] + cnt[i][2];
    run.role[i] = r == rbsf::ContactRole::kLifted || rising ? ContactRole::kOff
                  : slipSign(r) != 0                        ? ContactRole::kSlide
                                                            : ContactRole::kStick;
    run.relied[i] = r == rbsf::ContactRole::kStick || slipSign(r) != 0;
    const int sign = slipSign(r) == 0 ? 0 : (d > 1e-6 ? 1 : (d < -1e-6 ? -1 : 0));
    run.slide_direction[i] = sign;
    run.slide_rate[i] = sign == 0 ? 0.0 : std::abs(d) / run.duration;
    sticking += run.role[i] == ContactRole::kStick;
  }
  run.phase = sticking >= 2 ? Phase::kC : (sticking == 1 ? Phase::kP : Phase::kU);
}

/// What the re-simulation tells of each segment besides the steps themselves.
struct SegmentTally {
  std::vector<ModeCounts> counts;  ///< counts[s]: segment s's mode counts
  std::vector<VecC> xi_at;         ///< foot points at the segments' ends (xi_at[0]: the start)
};

/// What the runs were merged from, run by run.
struct RunTally {
  std::vector<ModeCounts> counts;      ///< the run's mode counts
  std::vector<VecC> xi_start, xi_end;  ///< foot points at its ends
};

// Why the plan gives no schedule, or nothing: no segments, a segment without a step, or
// (RunCut::kStatedRoles) a segment that states no roles.
std::string planError(const plan::Plan& plan, RunCut cut) {
  if (plan.segments.empty()) return "the plan has no segments";
  for (const plan::PlanSegment& seg : plan.segments)
    if (seg.steps < 1) return "a segment of the plan holds no simulator step";
  if (cut == RunCut::kStatedRoles &&
      !std::all_of(plan.segments.begin(), plan.segments.end(),
                   [](const plan::PlanSegment& g) { return planned(g.contacts); }))
    return "the plan does not state every segment's contact roles";
  return {};
}

// One pass of the simulator over the plan's segments: every step's state and contacts into
// `steps`, each segment's mode counts and the foot points at its end.
SegmentTally resimulate(const RbsfModel& model, const plan::Plan& plan, SimulatedSteps& steps) {
  const int m = model.numFingers();
  const Simulator sim(model, plan.simulator);
  SimulatorWorkspace ws(m);
  SimState state(plan.q0, VecQ::Zero(plan.q0.size()));
  ModelData data(m);
  steps.t.push_back(0.0);
  steps.q.push_back(state.q);
  steps.v.push_back(state.v);

  SegmentTally tally;
  tally.counts.resize(plan.segments.size());
  model.updateContacts(state.q, data);
  tally.xi_at.push_back(data.xi_hint);
  std::vector<long> seg_steps;
  std::vector<VecU> seg_tau;
  for (const plan::PlanSegment& seg : plan.segments) {
    seg_steps.push_back(seg.steps);
    seg_tau.push_back(seg.tau);
  }
  for (auto& c : tally.counts)
    for (auto& ci : c) ci.fill(0);
  HeldInputs inputs(seg_steps, seg_tau);
  rollout(sim, state, inputs.totalSteps(), ws, inputs,
          [&](const SimState& now, const StepReport& report, const VecU&, long n) {
            const std::size_t s = inputs.segment();
            const plan::PlanSegment& seg = plan.segments[s];
            for (int i = 0; i < m; ++i)
              ++tally.counts[s][i][static_cast<int>(report.contacts[i].mode)];
            steps.contacts.push_back(report.contacts);
            steps.t.push_back(steps.t.back() + seg.duration / std::max(1, seg.steps));
            steps.q.push_back(now.q);
            steps.v.push_back(now.v);
            if (inputs.endsSegment(n)) {
              model.updateContacts(now.q, data);
              tally.xi_at.push_back(data.xi_hint);
            }
            return true;
          });
  return tally;
}

// The mode each of the m contacts held for most of a segment with mode counts `c`.
std::array<int, kMaxFingers> majorityModes(int m, const ModeCounts& c) {
  std::array<int, kMaxFingers> key{};
  for (int i = 0; i < m; ++i)
    key[i] = static_cast<int>(std::max_element(c[i].begin(), c[i].end()) - c[i].begin());
  return key;
}

// The first segment of each run, then the number of segments. Runs are maximal sequences of
// segments with one phase letter and, when `split`, one majority mode per contact. With
// stated roles, runs are cut where the roles change instead: the roles are what the planner
// meant, the simulated letters flicker at hand-overs.
std::vector<int> groupRuns(const plan::Plan& plan, const std::vector<ModeCounts>& counts, int m,
                           bool stated, bool split) {
  const int S = static_cast<int>(plan.segments.size());
  std::vector<int> first_segment{0};
  for (int s = 1; s < S; ++s) {
    const bool cut =
        stated ? plan.segments[s].contacts != plan.segments[s - 1].contacts
               : plan.segments[s].phase != plan.segments[s - 1].phase ||
                     (split && majorityModes(m, counts[s]) != majorityModes(m, counts[s - 1]));
    if (cut) first_segment.push_back(s);
  }
  first_segment.push_back(S);
  return first_segment;
}

// groupRuns as `cut` asks, by letter alone when `intervals` are too few for the finer runs.
std::vector<int> cutRuns(const plan::Plan& plan, const std::vector<ModeCounts>& counts, int m,
                         RunCut cut, int intervals) {
  const bool stated = cut == RunCut::kStatedRoles;
  const bool split = cut == RunCut::kContactModes;
  std::vector<int> first_segment = groupRuns(plan, counts, m, stated, split);
  if (!stated && split && intervals < 2 * (static_cast<int>(first_segment.size()) - 1))
    first_segment = groupRuns(plan, counts, m, stated, false);
  return first_segment;
}

// The runs of segments first_segment[j] .. first_segment[j + 1] - 1, appended to `runs`
// (letter, start, duration and, when `stated`, the stated roles), with their mode counts and
// foot points.
RunTally mergeRuns(const plan::Plan& plan, const SegmentTally& segments,
                   const std::vector<int>& first_segment, int m, bool stated,
                   std::vector<PhaseRun>& runs) {
  RunTally tally;
  double t = 0.0;
  for (std::size_t j = 0; j + 1 < first_segment.size(); ++j) {
    PhaseRun run;
    run.phase = plan.segments[first_segment[j]].phase;
    run.start = t;
    ModeCounts c{};
    for (auto& ci : c) ci.fill(0);
    for (int s = first_segment[j]; s < first_segment[j + 1]; ++s) {
      run.duration += plan.segments[s].duration;
      for (int i = 0; i < m; ++i)
        for (int mode = 0; mode < 3; ++mode) c[i][mode] += segments.counts[s][i][mode];
    }
    t += run.duration;
    if (stated) run.planned = plan.segments[first_segment[j]].contacts;
    runs.push_back(run);
    tally.counts.push_back(c);
    tally.xi_start.push_back(segments.xi_at[first_segment[j]]);
    tally.xi_end.push_back(segments.xi_at[first_segment[j + 1]]);
  }
  return tally;
}

// Without stated roles, each contact's role by majority of its modes over the run, and the
// direction and mean rate of its foot point's change from `xi_start` to `xi_end`.
void majorityRoles(int m, const ModeCounts& cnt, const VecC& xi_start, const VecC& xi_end,
                   PhaseRun& run) {
  for (int i = 0; i < m; ++i) {
    const int st = cnt[i][static_cast<int>(ContactMode::kStick)];
    const int sl = cnt[i][static_cast<int>(ContactMode::kSlide)];
    const int off = cnt[i][static_cast<int>(ContactMode::kSeparated)];
    run.role[i] = (off >= st + sl) ? ContactRole::kOff
                                   : (st >= sl ? ContactRole::kStick : ContactRole::kSlide);
    const double d = wrappedDelta(xi_start[i], xi_end[i]);
    run.slide_direction[i] = d > 1e-6 ? 1 : (d < -1e-6 ? -1 : 0);
    run.slide_rate[i] = std::abs(d) / run.duration;
  }
}

// The majority roles made to agree with the run's letter: C at least two sticking (the most
// sticking ones), P exactly the one that sticks most, U none sticking (a sticking majority
// becomes sliding). Every contact that is not off is relied on; only sliders keep a slide.
void agreeWithLetter(int m, const ModeCounts& cnt, PhaseRun& run) {
  auto stickCount = [&](int i) { return cnt[i][static_cast<int>(ContactMode::kStick)]; };
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

// `intervals` (at least 2 per run) spread over the runs: 2 each, the rest in proportion to
// their durations over `total` (largest remainder); each run's first interval and the
// interval -> run map.
void spreadIntervals(int intervals, double total, Schedule& schedule) {
  const int R = static_cast<int>(schedule.runs.size());
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
}

// A failed build: no schedule, and why.
ScheduleResult failure(std::string error) {
  ScheduleResult result;
  result.error = std::move(error);
  return result;
}

// PhaseRun::at_rest of every run: the re-simulation's part speeds at the steps within it,
// against kSettling x the cell's rest.
void markRests(const MotionLimits& limits, Schedule& schedule) {
  const SimulatedSteps& steps = schedule.steps;
  std::size_t s = 0;
  for (PhaseRun& run : schedule.runs) {
    const double end = run.start + run.duration;
    run.at_rest = true;
    for (; s < steps.t.size() && steps.t[s] <= end + 1e-9; ++s) {
      if (steps.t[s] < run.start - 1e-9) continue;
      const VecQ& v = steps.v[s];
      if (std::hypot(v[layout::kX], v[layout::kY]) > kSettling * limits.rest_speed ||
          std::abs(v[layout::kPhi]) > kSettling * limits.rest_angular_speed)
        run.at_rest = false;
    }
    if (s > 0) --s;  // the boundary step belongs to the next run too
  }
}

}  // namespace

ContactRole Schedule::knotRole(int knot, int i) const {
  ContactRole r = ContactRole::kOff;
  if (knot > 0) r = role(knot - 1, i);
  if (knot < intervals() && strength(role(knot, i)) > strength(r)) r = role(knot, i);
  return r;
}

ScheduleResult buildSchedule(const RbsfModel& model, const plan::Plan& plan, int intervals,
                             RunCut cut) {
  const int m = model.numFingers();
  const bool stated = cut == RunCut::kStatedRoles;
  std::string error = planError(plan, cut);
  if (!error.empty()) return failure(std::move(error));
  ScheduleResult result;
  Schedule& schedule = result.schedule;
  const SegmentTally segments = resimulate(model, plan, schedule.steps);
  const std::vector<int> first_segment = cutRuns(plan, segments.counts, m, cut, intervals);
  const RunTally runs = mergeRuns(plan, segments, first_segment, m, stated, schedule.runs);
  const int R = static_cast<int>(schedule.runs.size());
  for (int j = 0; j < R; ++j) {
    PhaseRun& run = schedule.runs[j];
    if (stated) {
      statedRoles(m, runs.counts[j], runs.xi_start[j], runs.xi_end[j], run);
      continue;
    }
    majorityRoles(m, runs.counts[j], runs.xi_start[j], runs.xi_end[j], run);
    agreeWithLetter(m, runs.counts[j], run);
  }
  markRests(model.cell().motion_limits, schedule);
  if (intervals < 2 * R)
    return failure("settings.knots = " + std::to_string(intervals) +
                   " is fewer than 2 per phase run (" + std::to_string(R) + " runs)");
  spreadIntervals(intervals, plan.duration(), schedule);
  return result;
}

}  // namespace rbsf::trajopt
