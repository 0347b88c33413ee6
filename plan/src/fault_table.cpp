#include "rbsf/plan/fault_table.h"

#include <algorithm>
#include <cstdio>

namespace rbsf::plan {

FaultRow faultRow(const std::string& kind, const std::vector<TrialOutcome>& outcomes) {
  FaultRow row;
  row.kind = kind;
  std::vector<double> delays;
  for (const TrialOutcome& o : outcomes) {
    ++row.trials;
    switch (trialEnd(o)) {
      case TrialEnd::kDone:
        ++row.done;
        break;
      case TrialEnd::kHeld: {
        ++row.held;
        auto it = std::find_if(row.hold_reasons.begin(), row.hold_reasons.end(),
                               [&](const auto& r) { return r.first == o.hold; });
        if (it == row.hold_reasons.end())
          row.hold_reasons.emplace_back(o.hold, 1);
        else
          ++it->second;
        break;
      }
      case TrialEnd::kLost:
        ++row.lost;
        if (!(o.report_time >= 0.0 && o.report_time <= o.dropped_time + 0.05))
          ++row.lost_unreported;
        break;
      case TrialEnd::kOff:
        ++row.off;
        break;
    }
    if (o.fault_time >= 0.0) {
      ++row.with_fault;
      if (o.fault_seen_time >= 0.0) {
        ++row.seen;
        delays.push_back(o.fault_seen_time - o.fault_time);
      }
    }
  }
  if (!delays.empty()) {
    std::sort(delays.begin(), delays.end());
    row.median_seen = delays[delays.size() / 2];
    row.max_seen = delays.back();
  }
  return row;
}

std::vector<std::pair<std::string, Cell>> faultKinds(const Cell& cell) {
  std::vector<std::pair<std::string, Cell>> kinds;
  const Faults& f = cell.faults;
  auto alone = [&](const char* name, auto&& keep) {
    Cell c = cell;
    c.faults = Faults{};
    keep(c.faults);
    kinds.emplace_back(name, std::move(c));
  };
  if (f.pose_dropouts.rate > 0.0)
    alone("pose dropouts", [&](Faults& g) { g.pose_dropouts = f.pose_dropouts; });
  if (f.joint_spikes.rate > 0.0)
    alone("joint spikes", [&](Faults& g) { g.joint_spikes = f.joint_spikes; });
  if (f.missed_tick_rate > 0.0)
    alone("missed ticks", [&](Faults& g) { g.missed_tick_rate = f.missed_tick_rate; });
  if (f.force_cut_chance > 0.0)
    alone("force cut", [&](Faults& g) {
      g.force_cut_chance = f.force_cut_chance;
      g.force_cut_to = f.force_cut_to;
    });
  if (f.mass_error > 0.0) alone("mass error", [&](Faults& g) { g.mass_error = f.mass_error; });
  return kinds;
}

std::string faultTableText(const std::vector<FaultRow>& rows) {
  std::string out =
      "faults           trials   done   held   lost  (unreported)    off  done or held  "
      "fault flagged after (median, max)\n";
  char buf[256];
  for (const FaultRow& r : rows) {
    const double ok = r.trials > 0 ? 100.0 * (r.done + r.held) / r.trials : 0.0;
    std::snprintf(buf, sizeof buf, "%-15s %7d %6d %6d %6d  (%d)%*s %6d  %10.1f %%  ",
                  r.kind.c_str(), r.trials, r.done, r.held, r.lost, r.lost_unreported,
                  r.lost_unreported < 10 ? 10 : 9, "", r.off, ok);
    out += buf;
    if (r.with_fault == 0)
      out += "no fault acted";
    else if (r.seen == 0)
      out += "never flagged";
    else {
      std::snprintf(buf, sizeof buf, "%.0f ms, %.0f ms (%d of %d flagged)", 1e3 * r.median_seen,
                    1e3 * r.max_seen, r.seen, r.with_fault);
      out += buf;
    }
    if (!r.hold_reasons.empty()) {
      out += "; held for";
      for (std::size_t i = 0; i < r.hold_reasons.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%s %s %d", i == 0 ? "" : ",",
                      toString(r.hold_reasons[i].first), r.hold_reasons[i].second);
        out += buf;
      }
    }
    out += "\n";
  }
  return out;
}

}  // namespace rbsf::plan
