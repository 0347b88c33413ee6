#include "rbsf/bench/benchmark_log.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/input_file.h"

namespace rbsf::bench {

namespace {

constexpr const char* kRunIndex = "run index INTEGER";

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// Line reader with the label and line number for messages.
class Lines {
 public:
  Lines(const std::string& text, std::string label) : label_(std::move(label)) {
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) {
      if (!l.empty() && l.back() == '\r') l.pop_back();
      lines_.push_back(std::move(l));
    }
  }
  bool done() const { return pos_ >= lines_.size(); }
  const std::string& peek() const {
    if (done()) fail("unexpected end of file");
    return lines_[pos_];
  }
  std::string next() {
    const std::string& l = peek();
    ++pos_;
    return l;
  }
  /// "<count> <words>"; returns count.
  std::size_t count(const std::string& words) {
    const std::string l = next();
    std::size_t n = 0;
    int used = 0;
    if (std::sscanf(l.c_str(), "%zu %n", &n, &used) != 1 || !startsWithWords(l.substr(used), words))
      fail("expected '<count> " + words + "', got '" + l + "'", pos_);
    return n;
  }
  [[noreturn]] void fail(const std::string& msg, std::size_t line = 0) const {
    throw InputError(label_ + ":" + std::to_string(line ? line : pos_ + 1) +
                     ": not an OMPL benchmark log: " + msg);
  }

 private:
  static bool startsWithWords(const std::string& s, const std::string& words) {
    // "enum type" also matches "enum types"; "runs" matches "runs".
    return s.rfind(words, 0) == 0;
  }
  std::string label_;
  std::vector<std::string> lines_;
  std::size_t pos_ = 0;
};

bool isEnumCount(const std::string& l) {
  std::size_t n = 0;
  int used = 0;
  return std::sscanf(l.c_str(), "%zu %n", &n, &used) == 1 &&
         l.substr(used).rfind("enum type", 0) == 0;
}

std::vector<std::string> splitValues(const std::string& line) {
  // OMPL writes "v; " after every value.
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t p; (p = line.find("; ", start)) != std::string::npos; start = p + 2)
    out.push_back(line.substr(start, p - start));
  return out;
}

long runIndex(const LogRun& r) {
  const auto it = r.values.find(kRunIndex);
  return it == r.values.end() || it->second.empty() ? -1 : std::stol(it->second);
}

void setHeaderValue(std::vector<std::string>& header, const std::string& tail,
                    const std::string& value) {
  bool in_block = false;
  for (std::string& l : header) {
    if (l.rfind("<<<|", 0) == 0) in_block = true;
    if (!in_block && endsWith(l, tail)) l = value + tail;
    if (l.find("|>>>") != std::string::npos) in_block = false;
  }
}

double headerNumber(const std::vector<std::string>& header, const std::string& tail) {
  bool in_block = false;
  for (const std::string& l : header) {
    if (l.rfind("<<<|", 0) == 0) in_block = true;
    if (!in_block && endsWith(l, tail)) return std::atof(l.c_str());
    if (l.find("|>>>") != std::string::npos) in_block = false;
  }
  return 0.0;
}

}  // namespace

std::string ExperimentLog::name() const {
  for (const std::string& l : header)
    if (l.rfind("Experiment ", 0) == 0) return l.substr(11);
  return {};
}

std::size_t ExperimentLog::runCount() const {
  std::size_t n = 0;
  for (const PlannerLog& p : planners) n += p.runs.size();
  return n;
}

ExperimentLog parseLog(const std::string& text, const std::string& label) {
  Lines in(text, label);
  ExperimentLog log;
  while (!isEnumCount(in.peek())) log.header.push_back(in.next());
  if (log.name().empty()) in.fail("no 'Experiment <name>' line before the enums", 1);
  const std::size_t enums = in.count("enum type");
  for (std::size_t i = 0; i < enums; ++i) log.enums.push_back(in.next());
  const std::size_t planners = in.count("planners");
  for (std::size_t i = 0; i < planners; ++i) {
    PlannerLog p;
    p.name = in.next();
    const std::size_t common = in.count("common properties");
    for (std::size_t k = 0; k < common; ++k) p.common.push_back(in.next());
    const std::size_t props = in.count("properties for each run");
    std::vector<std::string> names;
    for (std::size_t k = 0; k < props; ++k) names.push_back(in.next());
    const std::size_t runs = in.count("runs");
    for (std::size_t r = 0; r < runs; ++r) {
      const std::vector<std::string> v = splitValues(in.next());
      if (v.size() != names.size())
        in.fail("a run has " + std::to_string(v.size()) + " values for " +
                std::to_string(names.size()) + " properties");
      LogRun run;
      for (std::size_t k = 0; k < names.size(); ++k) run.values[names[k]] = v[k];
      p.runs.push_back(std::move(run));
    }
    if (in.peek() != ".") {
      const std::size_t np = in.count("progress properties for each run");
      for (std::size_t k = 0; k < np; ++k) p.progress_names.push_back(in.next());
      const std::size_t pr = in.count("runs");
      if (pr != p.runs.size()) in.fail("progress data for a different number of runs");
      for (std::size_t r = 0; r < pr; ++r) p.runs[r].progress = in.next();
    }
    if (in.next() != ".") in.fail("expected '.' after a planner's runs");
    log.planners.push_back(std::move(p));
  }
  return log;
}

ExperimentLog readLog(const std::string& path) {
  return parseLog(readInputFile(path, "log file"), path);
}

std::string formatLog(const ExperimentLog& log) {
  std::ostringstream out;
  for (const std::string& l : log.header) out << l << '\n';
  out << log.enums.size() << (log.enums.size() == 1 ? " enum type" : " enum types") << '\n';
  for (const std::string& l : log.enums) out << l << '\n';
  out << log.planners.size() << " planners\n";
  for (const PlannerLog& p : log.planners) {
    out << p.name << '\n' << p.common.size() << " common properties\n";
    for (const std::string& l : p.common) out << l << '\n';
    std::set<std::string> names;
    for (const LogRun& r : p.runs)
      for (const auto& kv : r.values) names.insert(kv.first);
    out << names.size() << " properties for each run\n";
    for (const std::string& n : names) out << n << '\n';
    out << p.runs.size() << " runs\n";
    for (const LogRun& r : p.runs) {
      for (const std::string& n : names) {
        const auto it = r.values.find(n);
        if (it != r.values.end()) out << it->second;
        out << "; ";
      }
      out << '\n';
    }
    if (!p.progress_names.empty()) {
      out << p.progress_names.size() << " progress properties for each run\n";
      for (const std::string& n : p.progress_names) out << n << '\n';
      out << p.runs.size() << " runs\n";
      for (const LogRun& r : p.runs) out << r.progress << '\n';
    }
    out << ".\n";
  }
  return out.str();
}

void mergeLog(ExperimentLog& into, const ExperimentLog& from) {
  if (into.header.empty()) {
    into = from;
  } else {
    if (into.name() != from.name())
      throw InputError("cannot merge experiment '" + from.name() + "' into '" + into.name() + "'");
    const double total = headerNumber(into.header, " seconds spent to collect the data") +
                         headerNumber(from.header, " seconds spent to collect the data");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", total);
    setHeaderValue(into.header, " seconds spent to collect the data", buf);
    for (const std::string& e : from.enums) {  // union of the enums, by name
      const std::string name = e.substr(0, e.find('|'));
      if (std::none_of(into.enums.begin(), into.enums.end(),
                       [&](const std::string& f) { return f.substr(0, f.find('|')) == name; }))
        into.enums.push_back(e);
    }
    for (const PlannerLog& p : from.planners) {
      auto it = std::find_if(into.planners.begin(), into.planners.end(),
                             [&](const PlannerLog& q) { return q.name == p.name; });
      if (it == into.planners.end()) {
        into.planners.push_back(p);
        continue;
      }
      if (it->progress_names.empty()) it->progress_names = p.progress_names;
      it->runs.insert(it->runs.end(), p.runs.begin(), p.runs.end());
    }
  }
  std::size_t most = 0;
  for (PlannerLog& p : into.planners) {
    std::stable_sort(p.runs.begin(), p.runs.end(),
                     [](const LogRun& a, const LogRun& b) { return runIndex(a) < runIndex(b); });
    for (std::size_t k = 1; k < p.runs.size(); ++k)
      if (runIndex(p.runs[k]) >= 0 && runIndex(p.runs[k]) == runIndex(p.runs[k - 1]))
        throw InputError("experiment '" + into.name() + "', planner " + p.name + ": run " +
                         std::to_string(runIndex(p.runs[k])) + " appears twice");
    most = std::max(most, p.runs.size());
  }
  setHeaderValue(into.header, " runs per planner", std::to_string(most));
  setHeaderValue(into.header, " is the random seed", "0");
}

}  // namespace rbsf::bench
