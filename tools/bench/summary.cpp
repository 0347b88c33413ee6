#include "rbsf/bench/summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rbsf::bench {

namespace {

const std::string* value(const LogRun& r, const std::string& key) {
  const auto it = r.values.find(key);
  return it == r.values.end() || it->second.empty() ? nullptr : &it->second;
}

double real(const LogRun& r, const std::string& key, double fallback) {
  const std::string* v = value(r, key);
  return v ? std::atof(v->c_str()) : fallback;
}

bool flag(const LogRun& r, const std::string& key) {
  const std::string* v = value(r, key);
  return v && (*v == "1" || *v == "true");
}

std::string seconds(double t) {
  if (!std::isfinite(t)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", t);
  return buf;
}

}  // namespace

double quantile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return std::numeric_limits<double>::infinity();
  const double pos = p * static_cast<double>(sorted.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double w = pos - static_cast<double>(lo);
  if (w == 0.0 || !std::isfinite(sorted[hi])) return w == 0.0 ? sorted[lo] : sorted[hi];
  return sorted[lo] + w * (sorted[hi] - sorted[lo]);
}

std::vector<SummaryRow> summarize(const std::vector<ExperimentLog>& logs) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<SummaryRow> rows;
  for (const ExperimentLog& log : logs) {
    for (const PlannerLog& p : log.planners) {
      SummaryRow row;
      row.problem = log.name();
      row.planner = p.name.rfind("control_", 0) == 0 ? p.name.substr(8) : p.name;
      std::vector<double> times, durations, reductions, pivots;
      double props = 0.0, total_time = 0.0;
      for (const LogRun& r : p.runs) {
        ++row.runs;
        const bool solved = flag(r, "solved BOOLEAN");
        const double t = real(r, "time REAL", 0.0);
        row.solved += solved;
        times.push_back(solved ? t : inf);
        props += real(r, "propagations INTEGER", 0.0);
        total_time += t;
        if (solved && value(r, "solution duration REAL"))
          durations.push_back(real(r, "solution duration REAL", 0.0));
        if (solved && value(r, "pivots INTEGER")) pivots.push_back(real(r, "pivots INTEGER", 0.0));
        if (flag(r, "certified BOOLEAN")) ++row.certified;
        if (value(r, "optimizer success BOOLEAN")) {
          ++row.optimized;
          if (flag(r, "optimizer success BOOLEAN")) {
            ++row.optimizer_success;
            reductions.push_back(real(r, "cost reduction REAL", 0.0));
          }
        }
      }
      std::sort(times.begin(), times.end());
      std::sort(durations.begin(), durations.end());
      std::sort(reductions.begin(), reductions.end());
      std::sort(pivots.begin(), pivots.end());
      row.time_q1 = quantile(times, 0.25);
      row.time_median = quantile(times, 0.5);
      row.time_q3 = quantile(times, 0.75);
      row.propagations_per_second = total_time > 0.0 ? props / total_time : 0.0;
      if (!durations.empty()) row.duration_median = quantile(durations, 0.5);
      if (!pivots.empty()) row.pivots_median = quantile(pivots, 0.5);
      if (!reductions.empty()) row.cost_reduction_median = quantile(reductions, 0.5);
      rows.push_back(row);
    }
  }
  return rows;
}

std::string formatSummary(const std::vector<SummaryRow>& rows, bool optimize) {
  std::string out;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-16s %-8s %9s %7s %8s %8s %8s %9s %12s %7s", "problem",
                "planner", "solved", "success", "t q1[s]", "t med[s]", "t q3[s]", "prop/s",
                "duration[s]", "pivots");
  out += buf;
  if (optimize) out += "  opt ok  cost red.    cert.";
  out += '\n';
  for (const SummaryRow& r : rows) {
    char solved[32];
    std::snprintf(solved, sizeof solved, "%d/%d", r.solved, r.runs);
    char pivots[32] = "-";
    if (r.pivots_median >= 0) std::snprintf(pivots, sizeof pivots, "%g", r.pivots_median);
    std::snprintf(buf, sizeof buf, "%-16s %-8s %9s %6.0f%% %8s %8s %8s %9.0f %12s %7s",
                  r.problem.c_str(), r.planner.c_str(), solved,
                  r.runs ? 100.0 * r.solved / r.runs : 0.0, seconds(r.time_q1).c_str(),
                  seconds(r.time_median).c_str(), seconds(r.time_q3).c_str(),
                  r.propagations_per_second,
                  r.duration_median >= 0 ? seconds(r.duration_median).c_str() : "-", pivots);
    out += buf;
    if (optimize) {
      char opt[32];
      std::snprintf(opt, sizeof opt, "%d/%d", r.optimizer_success, r.optimized);
      std::snprintf(
          buf, sizeof buf, "  %6s  %8s", opt,
          r.optimizer_success
              ? (std::to_string(static_cast<int>(std::lround(100.0 * r.cost_reduction_median))) +
                 "%")
                    .c_str()
              : "-");
      out += buf;
      std::snprintf(opt, sizeof opt, "%d/%d", r.certified, r.optimized);
      std::snprintf(buf, sizeof buf, "  %7s", opt);
      out += buf;
    }
    out += '\n';
  }
  return out;
}

}  // namespace rbsf::bench
