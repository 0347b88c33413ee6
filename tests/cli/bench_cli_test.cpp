// rbsf-bench as a user runs it: an end-to-end run of the default suite with a Planner
// Arena database, shards whose union is the run list, parallel and sharded runs equal to a
// sequential one, and refused input. Bounded: short time limits, a few runs. Also the
// optimiser benchmark's command line (its runs take minutes: help and refusals only).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"
#include "rbsf/bench/benchmark_log.h"

namespace {

namespace fs = std::filesystem;
const std::string kBench = RBSF_BENCH_EXE;
const std::string kSuite = std::string(RBSF_SOURCE_DIR) + "/cells/problems/default.yaml";

using rbsf::cli_test::Result;
using rbsf::cli_test::slurp;

std::string scratch(const std::string& name) {
  const std::string dir =
      ::testing::TempDir() + "rbsf_bench_" + std::to_string(getpid()) + "_" + name;
  fs::remove_all(dir);
  return dir;
}

/// rbsf-bench with these arguments (cli_support.h's run).
Result run(const std::string& args) { return rbsf::cli_test::run(kBench + " " + args); }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::string sql(const std::string& db, const std::string& query) {
  const std::string out = scratch("sql");
  const int raw = std::system(("sqlite3 '" + db + "' \"" + query + "\" >" + out + " 2>&1").c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << query << ": " << slurp(out);
  return slurp(out);
}

TEST(RbsfBench, DefaultSuiteEndToEndWithPlannerArenaDatabase) {
  const std::string out = scratch("e2e");
  const Result r = run("--problems " + kSuite +
                       " --planners KPIECE1,RRT --runs 2 --time-limit 3 --jobs 2 --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  // One progress line per run.
  int progress = 0;
  for (const std::string& l : lines(r.err)) progress += l.rfind("[", 0) == 0;
  EXPECT_EQ(progress, 12) << r.err;
  // Planner Arena's tables, every run in them.
  const std::string db = out + "/benchmark.db";
  const std::string tables = sql(db, ".tables");
  for (const char* t : {"experiments", "plannerConfigs", "runs", "progress", "enums"})
    EXPECT_NE(tables.find(t), std::string::npos) << t << " missing: " << tables;
  EXPECT_EQ(sql(db, "SELECT COUNT(*) FROM runs;"), "12\n");
  EXPECT_EQ(sql(db, "SELECT COUNT(*) FROM experiments;"), "3\n");
  EXPECT_EQ(sql(db, "SELECT COUNT(DISTINCT seed) FROM runs;"), "12\n");
  EXPECT_EQ(sql(db, "SELECT COUNT(*) FROM runs WHERE propagations > 0 AND time > 0;"), "12\n");
  // Solved runs: OMPL's path check passes, its length (sum of control durations) equals
  // the re-simulated plan's duration, and the re-simulation reproduces the planner's states.
  EXPECT_EQ(sql(db,
                "SELECT COUNT(*) FROM runs WHERE solved = 1 AND (correct_solution != 1 OR "
                "abs(solution_length - solution_duration) > 1e-9 OR path_mismatch > 1e-9);"),
            "0\n");
  // A summary row per problem and planner.
  for (const char* problem : {"30deg", "90deg", "180deg"})
    for (const char* planner : {"KPIECE1", "RRT"}) {
      bool found = false;
      for (const std::string& l : lines(r.out)) {
        std::istringstream in(l);
        std::string p, q, solved;
        in >> p >> q >> solved;
        found |= p == problem && q == planner && solved.size() >= 3 && solved.substr(1) == "/2";
      }
      EXPECT_TRUE(found) << problem << " " << planner << ":\n" << r.out;
    }
  EXPECT_EQ(slurp(out + "/summary.txt") +
                "logs, Planner Arena database (benchmark.db) and "
                "summary.txt in " +
                out + "\n",
            r.out);
  for (const char* log : {"30deg.log", "90deg.log", "180deg.log"})
    EXPECT_TRUE(fs::exists(out + "/" + log)) << log;
  EXPECT_FALSE(fs::exists(out + "/.runs"));
}

TEST(RbsfBench, TheSupportPlannerRunsBesideKpieceOnTheSameProblem) {
  // The 30 degree turn alone, the support planner (an ompl::base::Planner) and KPIECE1 one
  // run each: both solve; the support run's path passes OMPL's check, its length is its plan's
  // duration (within the one control its last, shorter segment is rounded up to), and it
  // reports its expansions instead of propagations.
  const std::string out = scratch("support");
  fs::create_directories(out);
  const std::string suite = out + "/suite.yaml";
  std::ofstream(suite) << "problems:\n  - name: 30deg\n    cell: " << RBSF_SOURCE_DIR
                       << "/cells/default.yaml\n    start: 0.1,0.40,0\n"
                          "    goal: 0.1,0.40,-30deg\n";
  const Result r =
      run("--problems " + suite + " --planners Support,KPIECE1 --runs 1 --time-limit 600 --out " +
          out + "/bench");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string db = out + "/bench/benchmark.db";
  EXPECT_EQ(sql(db, "SELECT COUNT(*) FROM runs WHERE solved = 1;"), "2\n");
  EXPECT_EQ(sql(db,
                "SELECT correct_solution, abs(solution_length - solution_duration) < 0.005, "
                "expansions > 0, propagations FROM runs JOIN plannerConfigs ON "
                "runs.plannerid = plannerConfigs.id WHERE plannerConfigs.name LIKE '%Support%';"),
            "1|1|1|0\n");
  const Result bad = run("--problems " + suite + " --planners Supprot --out " + out + "/bad");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("Support"), std::string::npos) << bad.err;
}

TEST(RbsfBench, ShardsUnionIsTheRunList) {
  const std::string args = "--problems " + kSuite + " --planners KPIECE1,RRT,SST --runs 5 --list";
  const Result whole = run(args);
  ASSERT_EQ(whole.status, 0) << whole.err;
  std::vector<std::string> all = lines(whole.out);
  ASSERT_EQ(all.size(), 1u + 3 * 3 * 5);
  std::multiset<std::string> shards;
  for (int k = 1; k <= 4; ++k) {
    const Result s = run(args + " --shard " + std::to_string(k) + "/4");
    ASSERT_EQ(s.status, 0) << s.err;
    const auto l = lines(s.out);
    EXPECT_EQ(l.front(), all.front());  // header
    shards.insert(l.begin() + 1, l.end());
  }
  const std::multiset<std::string> expected(all.begin() + 1, all.end());
  EXPECT_EQ(shards, expected);  // every run exactly once, same seed
}

/// run index -> the deterministic fields of a solved run ("" when not solved).
std::map<int, std::string> solvedRuns(const std::string& log_path, int& seeds_checked) {
  const rbsf::bench::ExperimentLog log = rbsf::bench::readLog(log_path);
  std::map<int, std::string> out;
  for (const auto& p : log.planners)
    for (const auto& r : p.runs) {
      const auto& v = r.values;
      const int index = std::stoi(v.at("run index INTEGER"));
      seeds_checked += v.count("seed INTEGER");
      out[index] = v.at("solved BOOLEAN") == "1"
                       ? v.at("seed INTEGER") + " " + v.at("solution length REAL") + " " +
                             v.at("solution segments INTEGER") + " " +
                             v.at("propagations INTEGER") + " " + v.at("solution duration REAL")
                       : "";
    }
  return out;
}

TEST(RbsfBench, ParallelAndShardedRunsEqualTheSequentialRun) {
  const std::string suite = scratch("suite.yaml");
  std::ofstream(suite) << "problems:\n  - {name: p30, cell: " << RBSF_SOURCE_DIR
                       << "/cells/default.yaml, start: \"0.1,0.40,0\", goal: "
                          "\"0.1,0.40,-30deg\"}\n";
  const std::string common = "--problems " + suite + " --planners KPIECE1 --runs 4 --time-limit 10";
  const std::string seq = scratch("seq"), s1 = scratch("s1"), s2 = scratch("s2"),
                    merged = scratch("merged");
  ASSERT_EQ(run(common + " --jobs 1 --out " + seq).status, 0);
  ASSERT_EQ(run(common + " --jobs 2 --shard 1/2 --out " + s1).status, 0);
  ASSERT_EQ(run(common + " --jobs 2 --shard 2/2 --out " + s2).status, 0);
  const Result m = run("merge --out " + merged + " " + s1 + " " + s2);
  ASSERT_EQ(m.status, 0) << m.err;
  EXPECT_EQ(sql(merged + "/benchmark.db", "SELECT COUNT(*) FROM runs;"), "4\n");
  int seeds = 0;
  const auto a = solvedRuns(seq + "/p30.log", seeds);
  const auto b = solvedRuns(merged + "/p30.log", seeds);
  EXPECT_EQ(seeds, 8);
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  int compared = 0;
  for (const auto& [index, fields] : a) {
    // A run that hits its time limit in one and not the other (machine load) is not
    // deterministic; every run that reaches the goal in both must agree exactly.
    if (fields.empty() || b.at(index).empty()) continue;
    EXPECT_EQ(fields, b.at(index)) << "run " << index;
    ++compared;
  }
  EXPECT_GE(compared, 2) << "too few runs reached the goal to compare";
  // Merging a shard twice is refused.
  const Result twice = run("merge --out " + scratch("twice") + " " + s1 + " " + s1);
  EXPECT_EQ(twice.status, 2);
  EXPECT_NE(twice.err.find("appears twice"), std::string::npos) << twice.err;
}

TEST(RbsfBench, OptimizeRunsTheProductsRefinementAndRecordsItsCertificate) {
  // --optimize refines each exact plan as plan-reorientation does (optimise, certify the
  // planner's plan and the refinement, keep the better): the kept plan's certificate is in
  // the database and the summary.
  const std::string out = scratch("optimize");
  fs::create_directories(out);
  const std::string suite = out + "/suite.yaml";
  std::ofstream(suite) << "problems:\n  - name: 30deg\n    cell: " << RBSF_SOURCE_DIR
                       << "/cells/default.yaml\n    start: 0.1,0.40,0\n"
                          "    goal: 0.1,0.40,-30deg\n"
                          "    tolerances: {position: 0.01, angle: 2deg}\n";
  const Result r =
      run("--problems " + suite + " --planners KPIECE1 --runs 2 --time-limit 20 --optimize --out " +
          out + "/logs");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string db = out + "/logs/benchmark.db";
  const std::string solved = sql(db, "SELECT COUNT(*) FROM runs WHERE solved = 1;");
  ASSERT_NE(solved, "0\n") << "no exact plan within 20 s: nothing was refined";
  // Every solved run was refined and judged; a certified kept plan's lower confidence bound
  // is at least 0.95 (so is its rate), the sequential certificate ran whole batches of 64,
  // and a kept refinement converged.
  EXPECT_EQ(sql(db,
                "SELECT COUNT(*) FROM runs WHERE solved = 1 AND (certified IS NULL OR "
                "refined_chosen IS NULL OR certificate_success_rate IS NULL OR "
                "certificate_lower_bound IS NULL OR certificate_trials IS NULL);"),
            "0\n");
  EXPECT_EQ(sql(db,
                "SELECT COUNT(*) FROM runs WHERE certified = 1 AND "
                "(certificate_lower_bound < 0.95 OR certificate_success_rate < 0.95);"),
            "0\n");
  EXPECT_EQ(sql(db,
                "SELECT COUNT(*) FROM runs WHERE solved = 1 AND (certificate_trials % 64 != 0 "
                "OR certificate_trials < 64 OR certificate_trials > 512);"),
            "0\n");
  EXPECT_EQ(sql(db,
                "SELECT COUNT(*) FROM runs WHERE refined_chosen = 1 AND "
                "optimizer_success != 1;"),
            "0\n");
  const std::string certified = sql(db, "SELECT COUNT(*) FROM runs WHERE certified = 1;");
  const std::vector<std::string> table = lines(slurp(out + "/logs/summary.txt"));
  ASSERT_GE(table.size(), 2u);
  EXPECT_NE(table[0].find("cert."), std::string::npos) << table[0];
  const std::string cell =
      certified.substr(0, certified.size() - 1) + "/" + solved.substr(0, solved.size() - 1);
  EXPECT_NE(table[1].find(cell), std::string::npos) << table[1] << " (expected " << cell << ")";
}

TEST(RbsfBench, BadInputIsRefusedWithExitTwo) {
  const std::string bad_suite = scratch("bad.yaml");
  std::ofstream(bad_suite) << "problems:\n  - {name: x, cell: nowhere.yaml, start: \"0,0.4,0\", "
                              "goal: \"0,0.4,0\"}\n";
  struct Case {
    std::string args, needle;
  };
  const Case cases[] = {
      {"--runs 2", "--problems"},
      {"--problems " + kSuite + " --planners KPIECE1,PRM", "unknown planner 'PRM'"},
      {"--problems " + kSuite + " --runs 0", "--runs"},
      {"--problems " + kSuite + " --jobs 1.5", "--jobs"},
      {"--problems " + kSuite + " --time-limit=-1", "--time-limit"},
      {"--problems " + kSuite + " --shard 3/2", "--shard"},
      {"--problems /nonexistent.yaml", "/nonexistent.yaml"},
      {"--problems " + bad_suite, "problem x"},
      {"merge --out " + scratch("m"), "dirs"},
  };
  for (const Case& c : cases) {
    const Result r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
}

#ifdef RBSF_TRAJOPT_BENCH_EXE  // built with RBSF_BUILD_BENCHMARKS
TEST(RbsfTrajoptBench, HelpListsTheOptionsAndBadInputIsRefusedWithExitTwo) {
  const std::string kTrajoptBench = RBSF_TRAJOPT_BENCH_EXE;
  const Result help = rbsf::cli_test::run(kTrajoptBench + " --help");
  EXPECT_EQ(help.status, 0) << help.err;
  for (const char* option :
       {"--seeds", "--knots", "--only", "--split-runs", "--tolerance", "Exit status"})
    EXPECT_NE(help.out.find(option), std::string::npos) << option;
  struct Case {
    std::string args, needle;
  };
  const Case cases[] = {
      {"--seeds 0", "--seeds"},
      {"--knots 1", "--knots"},
      {"--only 45", "--only"},
      {"--max-solve-time=-1", "--max-solve-time"},
      {"--split-runs 2", "--split-runs"},
      {"--tolerance 0", "--tolerance"},
      {"--bogus 1", "--bogus"},
  };
  for (const Case& c : cases) {
    const Result r = rbsf::cli_test::run(kTrajoptBench + " " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
}
#endif

}  // namespace
