// rbsf-bench: planner benchmarks on problem suites with OMPL's benchmark machinery;
// OMPL .log files, a Planner Arena database and a summary table.
//
//   rbsf-bench --problems FILE [--planners LIST] [--runs N] [--time-limit S] [--jobs K]
//              [--optimize] [--shard k/N] [--list] [--out DIR]
//   rbsf-bench merge --out DIR SHARD_DIR...
//
// Every run is a child process (single_run.h: per-run seeds, crash isolation, --jobs).
// Exit status: 0 done; 2 bad input (option, problem file, cell, problem); 1 internal error.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <ompl/base/PlannerStatus.h>
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include "rbsf/bench/arena_database.h"
#include "rbsf/bench/benchmark_log.h"
#include "rbsf/bench/problem_suite.h"
#include "rbsf/bench/run_list.h"
#include "rbsf/bench/single_run.h"
#include "rbsf/bench/summary.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/tool_main.h"

namespace rbsf::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string problems, planners = "KPIECE1,RRT,SST,PDST", runs = "10", time_limit = "30",
                        jobs = "1", shard, out = "rbsf-bench-out";
  bool optimize = false, list = false;
  std::string merge_out;
  std::vector<std::string> merge_dirs;
};

int positiveInt(const std::string& text, const std::string& what, int most) {
  return static_cast<int>(tools::parseInteger(text, what, 1, most));
}

std::vector<std::string> parsePlanners(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string name; std::getline(in, name, ',');) {
    if (name != kSupportPlanner && !planner::parsePlanner(name))
      throw InputError("--planners: unknown planner '" + name +
                       "' (choose from KPIECE1, RRT, SST, EST, PDST, Support)");
    if (std::find(out.begin(), out.end(), name) != out.end())
      throw InputError("--planners: '" + name + "' is listed twice");
    out.push_back(name);
  }
  if (out.empty()) throw InputError("--planners: empty list");
  return out;
}

/// The log of a run whose process failed: OMPL's status "Crash", not solved.
LogRun crashRun(const RunSpec& spec, double seconds) {
  LogRun r;
  r.values["run index INTEGER"] = std::to_string(spec.run);
  r.values["seed INTEGER"] = std::to_string(spec.seed);
  r.values["time REAL"] = std::to_string(seconds);
  r.values["solved BOOLEAN"] = "0";
  r.values["status ENUM"] = std::to_string(static_cast<int>(ompl::base::PlannerStatus::CRASH));
  return r;
}

/// A header and enum list for a problem none of whose runs produced a log.
ExperimentLog emptyExperiment(const std::string& name, double time_limit) {
  ExperimentLog log;
  char host[256] = "UNKNOWN";
  gethostname(host, sizeof host - 1);
  log.header = {"Experiment " + name,
                std::string("Running on ") + host,
                "Starting at 1970-01-01T00:00:00",
                "<<<|",
                "|>>>",
                "0 is the random seed",
                std::to_string(time_limit) + " seconds per run",
                "4096 MB per run",
                "0 runs per planner",
                "0 seconds spent to collect the data"};
  std::string e = "status";
  for (int i = 0; i < ompl::base::PlannerStatus::TYPE_COUNT; ++i)
    e +=
        "|" +
        ompl::base::PlannerStatus(static_cast<ompl::base::PlannerStatus::StatusType>(i)).asString();
  log.enums = {e};
  return log;
}

/// Name of value `index` of enum `name` in a log's enum lines ("name|v0|v1|...").
std::string enumName(const std::vector<std::string>& enums, const std::string& name,
                     const std::string& index) {
  for (const std::string& e : enums) {
    if (e.rfind(name + "|", 0) != 0) continue;
    std::vector<std::string> values;
    std::istringstream in(e.substr(name.size() + 1));
    for (std::string v; std::getline(in, v, '|');) values.push_back(v);
    const int k = std::atoi(index.c_str());
    if (!index.empty() && k >= 0 && k < static_cast<int>(values.size())) return values[k];
  }
  return index;
}

std::string describe(const LogRun& r, double time_limit, const std::vector<std::string>& enums) {
  auto get = [&](const char* k) {
    const auto it = r.values.find(k);
    return it == r.values.end() ? std::string() : it->second;
  };
  char buf[256];
  const double t = std::atof(get("time REAL").c_str());
  if (get("status ENUM") == std::to_string(static_cast<int>(ompl::base::PlannerStatus::CRASH)))
    std::snprintf(buf, sizeof buf, "crashed after %.2f s", t);
  else if (get("solved BOOLEAN") == "1")
    std::snprintf(buf, sizeof buf, "solved in %.3f s, %s propagations, %.2f s of motion", t,
                  get("propagations INTEGER").c_str(),
                  std::atof(get("solution duration REAL").c_str()));
  else
    std::snprintf(buf, sizeof buf, "not solved in %.3g s (best distance %s), %s propagations",
                  time_limit,
                  get("best goal distance REAL").empty()
                      ? "-"
                      : get("best goal distance REAL").substr(0, 6).c_str(),
                  get("propagations INTEGER").c_str());
  std::string out = buf;
  if (!get("optimizer success BOOLEAN").empty())
    out +=
        get("optimizer success BOOLEAN") == "1"
            ? "; optimised, cost reduction " +
                  std::to_string(static_cast<int>(
                      std::lround(100.0 * std::atof(get("cost reduction REAL").c_str())))) +
                  "%"
            : "; optimiser: " + enumName(enums, "optimizer status", get("optimizer status ENUM"));
  return out;
}

/// Write the logs, the database and the summary into `dir`; print the summary.
void finish(const std::vector<ExperimentLog>& logs, const std::string& dir, bool optimize) {
  std::vector<std::string> paths;
  for (const ExperimentLog& log : logs) {
    paths.push_back((fs::path(dir) / (log.name() + ".log")).string());
    writeFileAtomically(paths.back(), formatLog(log), "--out");
  }
  makeArenaDatabase(paths, (fs::path(dir) / "benchmark.db").string());
  const std::string table = formatSummary(summarize(logs), optimize);
  writeFileAtomically((fs::path(dir) / "summary.txt").string(), table, "--out");
  std::printf("%s", table.c_str());
  std::printf("logs, Planner Arena database (benchmark.db) and summary.txt in %s\n", dir.c_str());
}

void makeDir(const std::string& dir, const std::string& what) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw InputError(what + ": cannot create the folder '" + dir + "'");
}

/// The suite's problems with their cells, each cell loaded once.
struct Suite {
  std::vector<BenchProblem> problems;
  std::vector<std::string> names;
  std::map<std::string, std::unique_ptr<RbsfModel>> models;  // by cell path

  const RbsfModel& model(const BenchProblem& p) const { return *models.at(p.cell_path); }
};

/// Every cell of the suite's problems loaded and every problem checked before any run (bad
/// input: exit 2).
void loadCells(const Options& o, Suite& suite) {
  for (const BenchProblem& p : suite.problems) {
    suite.names.push_back(p.name);
    auto& m = suite.models[p.cell_path];
    try {
      if (!m) m = std::make_unique<RbsfModel>(loadCell(p.cell_path));
      planner::ReorientationPlanner(*m, planner::PlannerSettings{}).checkProblem(p.problem);
    } catch (const InputError& e) {
      throw InputError(o.problems + ": problem " + p.name + ": " + e.what());
    }
  }
}

/// Run `spec` in this (child) process, its log written to `log`; exits 0, or 1 with a
/// message on stderr.
[[noreturn]] void runChild(const Suite& suite, const RunSpec& spec, const RunSettings& rs,
                           const std::string& log) {
  int code = 0;
  try {
    const BenchProblem& p = suite.problems[spec.problem];
    runSingle(p, suite.model(p), spec, rs, log);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rbsf-bench: run %zu: %s\n", spec.index, e.what());
    code = 1;
  }
  std::fflush(stderr);
  _exit(code);
}

/// The log of a finished child process: the one it wrote, or a crash record when it did
/// not exit 0.
ExperimentLog childLog(const Suite& suite, const RunSpec& spec, int status, double seconds,
                       const std::string& scratch, const RunSettings& rs) {
  const std::string path = scratch + "/" + std::to_string(spec.index) + ".log";
  ExperimentLog one;
  const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (ok) {
    one = readLog(path);
    std::remove(path.c_str());
  } else {
    one = emptyExperiment(suite.names[spec.problem], rs.time_limit);
    one.planners.push_back({"control_" + spec.planner, {}, {crashRun(spec, seconds)}, {}});
  }
  return one;
}

/// Runs `mine`, `jobs` at a time, each in a child process (crash isolation); the logs
/// merged per problem.
std::vector<ExperimentLog> runAll(const Suite& suite, const std::vector<RunSpec>& mine,
                                  const RunSettings& rs, int jobs, const std::string& scratch) {
  std::vector<ExperimentLog> logs(suite.problems.size());
  struct Child {
    RunSpec spec;
    Clock::time_point start;
  };
  std::map<pid_t, Child> children;
  std::size_t next = 0, finished = 0;
  // A child that overruns its limit by far (a planner ignoring the termination condition)
  // is killed and recorded as a crash.
  const double kill_after = 2.0 * rs.time_limit + 30.0;
  while (finished < mine.size()) {
    while (next < mine.size() && static_cast<int>(children.size()) < jobs) {
      const RunSpec& spec = mine[next++];
      const std::string log = scratch + "/" + std::to_string(spec.index) + ".log";
      std::fflush(stdout);
      std::fflush(stderr);
      const pid_t pid = fork();
      if (pid < 0) throw std::runtime_error("cannot start a run process");
      if (pid == 0) runChild(suite, spec, rs, log);
      children[pid] = {spec, Clock::now()};
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      for (auto& [cpid, c] : children)
        if (std::chrono::duration<double>(Clock::now() - c.start).count() > kill_after)
          kill(cpid, SIGKILL);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }
    const auto it = children.find(pid);
    if (it == children.end()) continue;
    const Child c = it->second;
    children.erase(it);
    ++finished;
    const double seconds = std::chrono::duration<double>(Clock::now() - c.start).count();
    const ExperimentLog one = childLog(suite, c.spec, status, seconds, scratch, rs);
    mergeLog(logs[c.spec.problem], one);
    const LogRun& run = one.planners.front().runs.front();
    std::fprintf(stderr, "[%zu/%zu] %s %s run %d (seed %u): %s\n", finished, mine.size(),
                 suite.names[c.spec.problem].c_str(), c.spec.planner.c_str(), c.spec.run,
                 c.spec.seed, describe(run, rs.time_limit, one.enums).c_str());
  }
  return logs;
}

int runBenchmarks(const Options& o) {
  Suite suite;
  suite.problems = loadProblemSuite(o.problems);
  const std::vector<std::string> planners = parsePlanners(o.planners);
  const int runs = positiveInt(o.runs, "--runs", 100000);
  const int jobs = positiveInt(o.jobs, "--jobs", 256);
  RunSettings rs;
  rs.time_limit = tools::parseNumber(o.time_limit, "--time-limit");
  if (rs.time_limit <= 0.0) throw InputError("--time-limit: must be positive");
  rs.optimize = o.optimize;
  int shard_k = 1, shard_n = 1;
  if (!o.shard.empty()) parseShard(o.shard, "--shard", shard_k, shard_n);
  loadCells(o, suite);

  const std::vector<RunSpec> all = makeRunList(suite.names, planners, runs);
  const std::vector<RunSpec> mine = shard_n > 1 ? shardOf(all, shard_k, shard_n) : all;
  if (o.list) {
    std::printf("index,problem,planner,run,seed\n");
    for (const RunSpec& r : mine)
      std::printf("%zu,%s,%s,%d,%u\n", r.index, suite.names[r.problem].c_str(), r.planner.c_str(),
                  r.run, r.seed);
    return 0;
  }
  makeDir(o.out, "--out");
  const std::string scratch = (fs::path(o.out) / ".runs").string();
  makeDir(scratch, "--out");

  std::fprintf(stderr,
               "rbsf-bench: %zu runs%s (%zu problems x %zu planners x %d), %d job%s, "
               "time limit %g s\n",
               mine.size(), shard_n > 1 ? (" in shard " + o.shard).c_str() : "",
               suite.problems.size(), planners.size(), runs, jobs, jobs > 1 ? "s" : "",
               rs.time_limit);
  std::vector<ExperimentLog> logs = runAll(suite, mine, rs, jobs, scratch);
  std::error_code ec;
  fs::remove_all(scratch, ec);
  std::vector<ExperimentLog> done;
  for (std::size_t p = 0; p < logs.size(); ++p)
    if (!logs[p].header.empty()) done.push_back(std::move(logs[p]));
  finish(done, o.out, o.optimize);
  return 0;
}

int mergeShards(const Options& o) {
  if (o.merge_dirs.empty()) throw InputError("merge: give the shards' output folders");
  std::vector<ExperimentLog> logs;
  bool optimize = false;
  for (const std::string& dir : o.merge_dirs) {
    if (!fs::is_directory(dir)) throw InputError("merge: '" + dir + "' is not a folder");
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".log") files.push_back(e.path().string());
    if (files.empty()) throw InputError("merge: no .log files in '" + dir + "'");
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) {
      const ExperimentLog log = readLog(f);
      auto it = std::find_if(logs.begin(), logs.end(),
                             [&](const ExperimentLog& l) { return l.name() == log.name(); });
      if (it == logs.end()) {
        logs.emplace_back();
        it = logs.end() - 1;
      }
      try {
        mergeLog(*it, log);
      } catch (const InputError& e) {
        throw InputError(f + ": " + e.what() + " (the same shard given twice?)");
      }
      for (const PlannerLog& p : log.planners)
        for (const LogRun& r : p.runs) optimize |= r.values.count("optimizer success BOOLEAN") > 0;
    }
  }
  makeDir(o.merge_out, "merge --out");
  finish(logs, o.merge_out, optimize);
  return 0;
}

int run(int argc, char** argv) {
  CLI::App app{
      "Benchmark the reorientation planners on a problem suite with OMPL's benchmark "
      "machinery: one .log file per problem (OMPL's format), a Planner Arena database "
      "(benchmark.db, made by ompl_benchmark_statistics) and a summary table, in --out. "
      "Every run has its own process and a seed fixed by (problem, planner, run index), so "
      "--jobs and --shard give the same runs as one sequential run.",
      "rbsf-bench"};
  app.footer(std::string(tools::kExitStatusHelp) +
             "\nShards of a large sweep: run rbsf-bench --shard k/N --out DIR_k for k = 1..N "
             "(e.g. a Slurm job array), then rbsf-bench merge --out DIR DIR_1 ... DIR_N.");
  Options o;
  app.add_option("--problems", o.problems,
                 "problem suite (YAML), e.g. cells/problems/default.yaml");
  app.add_option(
      "--planners", o.planners,
      "comma-separated planners: KPIECE1, RRT, SST, EST, PDST, Support (the support planner, "
      "support_ompl_planner.h) (default KPIECE1,RRT,SST,PDST)");
  app.add_option("--runs", o.runs, "runs per problem and planner (default 10)");
  app.add_option("--time-limit", o.time_limit, "seconds per run (default 30)");
  app.add_option("--jobs", o.jobs, "runs in parallel (default 1)");
  app.add_flag("--optimize", o.optimize, "refine each exact plan with the trajectory optimiser");
  app.add_option("--shard", o.shard, "run only shard k of N of the run list (k/N)");
  app.add_flag("--list", o.list, "print the (shard's) run list as CSV and exit");
  app.add_option("--out", o.out, "output folder (default rbsf-bench-out)");
  CLI::App* merge = app.add_subcommand("merge", "merge shards' output folders into one");
  merge->add_option("--out", o.merge_out, "output folder")->required();
  merge->add_option("dirs", o.merge_dirs, "the shards' output folders")->required();
  tools::parseCommandLine(app, argc, argv);
  if (merge->parsed()) return mergeShards(o);
  if (o.problems.empty()) throw InputError("--problems is required");
  return runBenchmarks(o);
}

}  // namespace
}  // namespace rbsf::bench

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf-bench", argc, argv, rbsf::bench::run);
}
