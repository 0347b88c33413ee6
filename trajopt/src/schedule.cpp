#include "rbsf/trajopt/schedule.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace rbsf::trajopt {

namespace {

int strength(ContactRole r) { return static_cast<int>(r); }

// Wrapped difference b - a in (-pi, pi].
double wrappedDelta(double a, double b) { return std::remainder(b - a, 2.0 * M_PI); }

}  // namespace

ContactRole Schedule::knotRole(int knot, int i) const {
  ContactRole r = ContactRole::kOff;
  if (knot > 0) r = role(knot - 1, i);
  if (knot < intervals() && strength(role(knot, i)) > strength(r)) r = role(knot, i);
  return r;
}

bool buildSchedule(const RbsfModel& model, const planner::Plan& plan, int intervals,
                   Schedule& schedule, std::string& why) {
  const int m = model.numFingers();
  schedule = Schedule{};
  if (plan.segments.empty()) {
    why = "the plan has no segments";
    return false;
  }
  SimulatorSettings ss;
  ss.time_step = plan.time_step;
  const Simulator sim(model, ss);
  SimulatorWorkspace ws(m);
  SimState state(plan.q0, VecQ::Zero(plan.q0.size()));
  StepReport report;
  ModelData data(m);

  // Mode counts per run: [run][contact][mode].
  std::vector<std::array<std::array<int, 3>, kMaxFingers>> counts;
  std::vector<VecC> xi_start, xi_end;
  model.updateContacts(state.q, data);
  double t = 0.0;
  for (std::size_t s = 0; s < plan.segments.size(); ++s) {
    const planner::PlanSegment& seg = plan.segments[s];
    if (schedule.runs.empty() || schedule.runs.back().phase != seg.phase) {
      PhaseRun run;
      run.phase = seg.phase;
      run.start = t;
      schedule.runs.push_back(run);
      counts.emplace_back();
      for (auto& c : counts.back()) c.fill(0);
      xi_start.push_back(data.xi_hint);
    }
    schedule.runs.back().duration += seg.duration;
    t += seg.duration;
    for (int k = 0; k < seg.steps; ++k) {
      sim.step(state, seg.tau, ws, &report);
      for (int i = 0; i < m; ++i) ++counts.back()[i][static_cast<int>(report.contacts[i].mode)];
    }
    model.updateContacts(state.q, data);
    if (xi_end.size() < schedule.runs.size()) xi_end.emplace_back();
    xi_end.back() = data.xi_hint;
  }

  const int R = static_cast<int>(schedule.runs.size());
  for (int j = 0; j < R; ++j) {
    PhaseRun& run = schedule.runs[j];
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
    for (int i = 0; i < m; ++i)
      if (run.role[i] != ContactRole::kSlide) {
        run.slide_direction[i] = 0;
        run.slide_rate[i] = 0.0;
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
