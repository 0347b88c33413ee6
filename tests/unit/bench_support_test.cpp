// rbsf-bench's pieces: the run list and its shards, OMPL log parsing/merging, the
// summary's quantiles, problem files, and the absolute goal angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>

#include "rbsf/bench/benchmark_log.h"
#include "rbsf/bench/problem_suite.h"
#include "rbsf/bench/run_list.h"
#include "rbsf/bench/summary.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/planner/kinodynamic/goal.h"

namespace rbsf::bench {
namespace {

const std::vector<std::string> kProblems = {"30deg", "90deg", "180deg"};
const std::vector<std::string> kPlanners = {"KPIECE1", "RRT", "SST"};

TEST(RunList, ShardsPartitionTheRunListAndKeepSeeds) {
  const std::vector<RunSpec> all = makeRunList(kProblems, kPlanners, 7);
  ASSERT_EQ(all.size(), 3u * 3u * 7u);
  for (int n : {1, 2, 3, 4, 7, 10, 100}) {
    std::multiset<std::size_t> seen;
    std::size_t least = all.size(), most = 0;
    for (int k = 1; k <= n; ++k) {
      const std::vector<RunSpec> s = shardOf(all, k, n);
      least = std::min(least, s.size());
      most = std::max(most, s.size());
      for (const RunSpec& r : s) {
        seen.insert(r.index);
        const RunSpec& same = all[r.index];  // the shard's entry is the list's entry
        EXPECT_EQ(r.problem, same.problem);
        EXPECT_EQ(r.planner, same.planner);
        EXPECT_EQ(r.run, same.run);
        EXPECT_EQ(r.seed, same.seed);
      }
    }
    EXPECT_EQ(seen.size(), all.size()) << n;  // union is the list ...
    EXPECT_EQ(std::set<std::size_t>(seen.begin(), seen.end()).size(), all.size()) << n;  // once
    EXPECT_LE(most - least, 1u) << n;
  }
}

TEST(RunList, SeedDependsOnlyOnProblemPlannerAndRun) {
  const std::vector<RunSpec> a = makeRunList(kProblems, kPlanners, 5);
  const std::vector<RunSpec> b = makeRunList({"180deg"}, {"SST", "KPIECE1"}, 3);
  for (const RunSpec& r : b) {
    const auto it = std::find_if(a.begin(), a.end(), [&](const RunSpec& s) {
      return kProblems[s.problem] == "180deg" && s.planner == r.planner && s.run == r.run;
    });
    ASSERT_NE(it, a.end());
    EXPECT_EQ(it->seed, r.seed);
  }
  std::set<std::uint32_t> seeds;
  for (const RunSpec& r : a) {
    EXPECT_NE(r.seed, 0u);
    seeds.insert(r.seed);
  }
  EXPECT_EQ(seeds.size(), a.size());  // no two runs share a seed here
}

TEST(RunList, ShardTextIsChecked) {
  int k = 0, n = 0;
  parseShard("2/5", "--shard", k, n);
  EXPECT_EQ(k, 2);
  EXPECT_EQ(n, 5);
  for (const char* bad : {"0/3", "4/3", "1", "a/b", "1/0", "1/2x", "-1/2"})
    EXPECT_THROW(parseShard(bad, "--shard", k, n), InputError) << bad;
}

std::string sampleLog(const std::string& name, const std::vector<int>& runs) {
  std::string text = "OMPL version 1.5.2\nExperiment " + name +
                     "\nRunning on host\nStarting at 2026-01-01T00:00:00\n<<<|\nsetup "
                     "3 runs per planner (inside the block: kept)\n|>>>\n7 is the random seed\n"
                     "5 seconds per run\n4096 MB per run\n" +
                     std::to_string(runs.size()) +
                     " runs per planner\n2.5 seconds spent to collect the data\n1 enum type\n"
                     "status|Unknown|Crash\n1 planners\ncontrol_KPIECE1\n1 common properties\n"
                     "goal_bias = 0.05\n3 properties for each run\nrun index INTEGER\n"
                     "solved BOOLEAN\ntime REAL\n" +
                     std::to_string(runs.size()) + " runs\n";
  for (int r : runs)
    text += std::to_string(r) + "; " + (r % 2 ? "1" : "0") + "; " + (r % 2 ? "0.5" : "") + "; \n";
  return text + ".\n";
}

TEST(BenchmarkLog, ParseFormatRoundTrips) {
  const std::string text = sampleLog("p", {0, 1, 2});
  const ExperimentLog log = parseLog(text, "x.log");
  EXPECT_EQ(log.name(), "p");
  ASSERT_EQ(log.planners.size(), 1u);
  ASSERT_EQ(log.planners[0].runs.size(), 3u);
  EXPECT_EQ(log.planners[0].runs[0].values.at("time REAL"), "");  // no value: NULL
  EXPECT_EQ(log.planners[0].runs[1].values.at("time REAL"), "0.5");
  EXPECT_EQ(formatLog(log), text);
}

TEST(BenchmarkLog, MergedShardsEqualTheWholeLog) {
  ExperimentLog merged;
  mergeLog(merged, parseLog(sampleLog("p", {1, 3}), "a"));
  mergeLog(merged, parseLog(sampleLog("p", {0, 2, 4}), "b"));
  ExperimentLog whole;
  mergeLog(whole, parseLog(sampleLog("p", {0, 1, 2, 3, 4}), "c"));
  ASSERT_EQ(merged.planners[0].runs.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k)
    EXPECT_EQ(merged.planners[0].runs[k].values, whole.planners[0].runs[k].values) << k;
  const std::string text = formatLog(merged);
  EXPECT_NE(text.find("\n5 runs per planner\n"), std::string::npos);
  EXPECT_NE(text.find("\n0 is the random seed\n"), std::string::npos);
  EXPECT_NE(text.find("setup 3 runs per planner (inside the block: kept)"), std::string::npos);
  EXPECT_NE(text.find("\n5 seconds spent to collect"), std::string::npos);  // 2.5 + 2.5
}

TEST(BenchmarkLog, MergeRefusesDuplicatesAndOtherExperiments) {
  ExperimentLog log;
  mergeLog(log, parseLog(sampleLog("p", {0, 1}), "a"));
  ExperimentLog again = log;
  EXPECT_THROW(mergeLog(again, parseLog(sampleLog("p", {1}), "b")), InputError);
  EXPECT_THROW(mergeLog(log, parseLog(sampleLog("q", {2}), "b")), InputError);
}

TEST(BenchmarkLog, MalformedLogsNameTheLine) {
  std::string text = sampleLog("p", {0});
  text.replace(text.find("1 runs\n"), 7, "2 runs\n");
  try {
    parseLog(text, "bad.log");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.log:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseLog("hello\n", "x.log"), InputError);
}

TEST(Summary, QuantilesInterpolateAndPropagateUnsolved) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4, 5}, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4, 5}, 0.25), 2.0);
  EXPECT_DOUBLE_EQ(quantile({1, 3}, 0.75), 2.5);
  EXPECT_DOUBLE_EQ(quantile({1, 2, inf}, 0.5), 2.0);
  EXPECT_EQ(quantile({1, 2, inf}, 0.75), inf);
  EXPECT_EQ(quantile({}, 0.5), inf);
}

TEST(Summary, RowsCountRunsAndSolved) {
  ExperimentLog log;
  mergeLog(log, parseLog(sampleLog("p", {0, 1, 2, 3}), "a"));
  // Pivots of the solved runs only (an unsolved run's plan is no answer).
  std::vector<LogRun>& runs = log.planners[0].runs;
  runs[0].values["pivots INTEGER"] = "9";
  runs[1].values["pivots INTEGER"] = "2";
  runs[3].values["pivots INTEGER"] = "4";
  const std::vector<SummaryRow> rows = summarize({log});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].planner, "KPIECE1");
  EXPECT_EQ(rows[0].runs, 4);
  EXPECT_EQ(rows[0].solved, 2);  // runs 1 and 3
  EXPECT_DOUBLE_EQ(rows[0].time_q1, 0.5);
  EXPECT_TRUE(std::isinf(rows[0].time_q3));
  EXPECT_DOUBLE_EQ(rows[0].pivots_median, 3.0);
  EXPECT_NE(formatSummary(rows, false).find("pivots"), std::string::npos);
}

TEST(ProblemSuite, ShippedSuitesLoad) {
  const auto def = loadProblemSuite(RBSF_SOURCE_DIR "/cells/problems/default.yaml");
  ASSERT_EQ(def.size(), 3u);
  EXPECT_EQ(def[2].name, "180deg");
  EXPECT_NEAR(def[2].problem.goal.phi, M_PI, 1e-15);
  EXPECT_NEAR(def[0].problem.tolerance.angle, 2.0 * M_PI / 180, 1e-15);
  EXPECT_EQ(def[0].cell_path, RBSF_SOURCE_DIR "/cells/default.yaml");
  const auto quarter = loadProblemSuite(RBSF_SOURCE_DIR "/cells/problems/quarter.yaml");
  ASSERT_EQ(quarter.size(), 2u);
  EXPECT_NEAR(quarter[0].problem.goal.phi, M_PI / 2, 1e-15);
  EXPECT_NEAR(quarter[1].problem.goal.phi, -M_PI / 2, 1e-15);
  const auto hard = loadProblemSuite(RBSF_SOURCE_DIR "/cells/problems/hard.yaml");
  ASSERT_EQ(hard.size(), 5u);
  int absolute = 0;
  for (const BenchProblem& p : hard) absolute += p.problem.absolute_angle;
  EXPECT_EQ(absolute, 1);
}

TEST(ProblemSuite, BadFilesNameFileProblemAndKey) {
  struct Case {
    std::string body, needle;
  };
  const std::string ok = "cell: ../default.yaml, start: \"0.1,0.4,0\", goal: \"0.1,0.4,-30deg\"";
  const Case cases[] = {
      {"problems: []", "non-empty list"},
      {"problems:\n  - {name: a, " + ok + ", colour: red}", "unknown key problems[0].colour"},
      {"problems:\n  - {name: a, cell: x.yaml, start: \"0.1,0.4,0\"}",
       "missing key problems[0].goal"},
      {"problems:\n  - {name: a, cell: x.yaml, start: \"0.1,0.4\", goal: \"0,0,0\"}",
       "problems[0].start"},
      {"problems:\n  - {name: a, " + ok + "}\n  - {name: a, " + ok + "}", "duplicate problem name"},
      {"problems:\n  - {name: \"a b\", " + ok + "}", "name 'a b'"},
      {"problems:\n  - {name: a, " + ok + ", goal_angle: round}", "goal_angle"},
      {"problems:\n  - {name: a, " + ok + ", tolerances: {angle: -1deg}}", "tolerances.angle"},
  };
  for (const Case& c : cases) {
    const std::string path = ::testing::TempDir() + "suite.yaml";
    std::ofstream(path) << c.body << "\n";
    try {
      loadProblemSuite(path);
      ADD_FAILURE() << "accepted: " << c.body;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.needle), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
    }
  }
}

TEST(GoalAngle, AbsoluteGoalDoesNotWrap) {
  const double deg = M_PI / 180;
  // A part turned by +90 deg is at the -270 deg goal's pose but not at its turn.
  EXPECT_NEAR(planner::goalAngleError(90 * deg, -270 * deg, false), 0.0, 1e-12);
  EXPECT_NEAR(planner::goalAngleError(90 * deg, -270 * deg, true), 360 * deg, 1e-12);
  EXPECT_NEAR(planner::goalAngleError(-269 * deg, -270 * deg, true), 1 * deg, 1e-12);
}

}  // namespace
}  // namespace rbsf::bench
