// rbsf-replay: a plan's certificate on a cell. On the planning cell with the plan's seed
// and trials it is the plan file's certificate; on a cell whose part is heavier the same
// plan fails and the report says where the part left its path; bad input exits 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.h"

namespace rbsf::cli_test {
namespace {

const std::string kReplay = RBSF_REPLAY_EXE;
const std::string kPlanExe = RBSF_PLAN_EXE;
const std::string kCellsDir = std::string(RBSF_SOURCE_DIR) + "/cells/";

/// The 15 degree plan of the planner tests (seed 7), certified with 6 trials of seed 3.
const std::string& smallPlan() {
  static const std::string path = [] {
    const std::string out = writeTemp("replay_plan.json", "");
    const Result r = run(kPlanExe + " --cell " + kCellsDir +
                         "default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --seed 4"
                         " --time-limit 3600 --max-propagations 200000 --quiet --no-optimize"
                         " --trials 6 --trial-seed 3 "
                         "--planner KPIECE1 --attempts 1"
                         " --out " +
                         out);
    EXPECT_TRUE(r.status == 0 || r.status == 4) << r.err;
    return out;
  }();
  return path;
}

TEST(Replay, OnThePlanningCellItReproducesThePlansCertificate) {
  const std::string out = writeTemp("replay.json", ""), csv = writeTemp("replay.csv", "");
  const Result r = run(kReplay + " --cell " + kCellsDir + "default.yaml --plan " + smallPlan() +
                       " --trials 6 --seed 3 --out " + out + " --csv " + csv);
  const auto plan = nlohmann::json::parse(slurp(smallPlan()));
  const auto report = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(report["certificate"], plan["certificate"]);  // every number, to the last bit
  EXPECT_EQ(r.status, plan["certificate"]["certified"].get<bool>() ? 0 : 4) << r.err;
  EXPECT_NE(r.out.find("certificate (part feedback, 6 trials, seed 3)"), std::string::npos)
      << r.out;
  // The worst trial's trajectory: the simulation's CSV columns, a row per step.
  const std::string text = slurp(csv);
  EXPECT_EQ(text.substr(0, text.find(',')), "t");
  EXPECT_GT(std::count(text.begin(), text.end(), '\n'), 500);
  // Another seed draws other trials.
  const std::string other = writeTemp("replay_other.json", "");
  run(kReplay + " --cell " + kCellsDir + "default.yaml --plan " + smallPlan() +
      " --trials 6 --seed 4 --out " + other);
  EXPECT_NE(nlohmann::json::parse(slurp(other))["certificate"]["worst"],
            plan["certificate"]["worst"]);
}

TEST(Replay, AHeavierPartFailsAndTheReportSaysWhereItLeftThePath) {
  // The same cell with 30 % more part mass: the plan's inputs were made for the lighter
  // part, and the law cannot make up for it.
  std::ifstream in(kCellsDir + "default.yaml");
  std::string cell((std::istreambuf_iterator<char>(in)), {});
  const std::string from = "mass: 24.0", to = "mass: 31.2";
  ASSERT_NE(cell.find(from), std::string::npos);
  cell.replace(cell.find(from), from.size(), to);
  const std::string heavy = writeTemp("heavy.yaml", cell);
  const std::string out = writeTemp("replay_heavy.json", "");
  const Result r = run(kReplay + " --cell " + heavy + " --plan " + smallPlan() +
                       " --trials 6 --seed 3 --out " + out);
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_NE(r.err.find("NOT certified"), std::string::npos) << r.err;
  const auto c = nlohmann::json::parse(slurp(out))["certificate"];
  EXPECT_LT(c["successes"].get<int>(), 6);
  ASSERT_TRUE(c["worst"].contains("departure_time")) << c["worst"];
  EXPECT_GE(c["worst"]["departure_time"].get<double>(), 0.0);
  EXPECT_NE(r.out.find("left the planned path at t = "), std::string::npos) << r.out;
}

TEST(Replay, TheSequentialDefaultSaysHowItStopped) {
  // The kinodynamic plan breaks the cell's motion limits: whatever its trials it cannot be
  // certified, so the sequential certificate stops after its first batch (here of 8).
  const std::string out = writeTemp("replay_sequential.json", "");
  const Result r = run(kReplay + " --cell " + kCellsDir + "default.yaml --plan " + smallPlan() +
                       " --trial-batch 8 --max-trials 40 --out " + out);
  EXPECT_EQ(r.status, 4) << r.err;
  const auto c = nlohmann::json::parse(slurp(out))["certificate"];
  EXPECT_EQ(c["trials"], 8);
  EXPECT_EQ(c["sequential"]["batch"], 8);
  EXPECT_EQ(c["sequential"]["max_trials"], 40);
  EXPECT_EQ(c["confidence"], 0.95);
  EXPECT_GE(c["lower_bound"].get<double>(), 0.0);
  EXPECT_LE(c["lower_bound"].get<double>(), c["success_rate"].get<double>());
  EXPECT_NE(r.out.find("sequential, batches of 8 up to 40 trials: stopped after 8, the plan fails "
                       "its motion limits or holding"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("% lower confidence bound "), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("NOT certified: "), std::string::npos) << r.err;
}

TEST(Replay, OpenLoopIsTheLawNamed) {
  const std::string out = writeTemp("replay_open.json", "");
  const Result r = run(kReplay + " --cell " + kCellsDir + "default.yaml --plan " + smallPlan() +
                       " --trials 2 --open-loop --out " + out);
  EXPECT_TRUE(r.status == 0 || r.status == 4) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(out))["certificate"]["law"], "open loop");
}

TEST(Replay, BadInputExitsTwoAndWritesNothing) {
  // A plan for three fingers on a two-finger cell.
  std::ifstream in(kCellsDir + "default.yaml");
  std::string cell((std::istreambuf_iterator<char>(in)), {});
  const std::string finger =
      "  - {r:  0.20, stroke: [0.05, 0.55], mass: 2.0, force_limit: 800.0}\n";
  ASSERT_NE(cell.find(finger), std::string::npos);
  cell.erase(cell.find(finger), finger.size());
  const std::string two = writeTemp("two_fingers.yaml", cell);
  const std::string base = kReplay + " --plan " + smallPlan() + " ";
  struct Case {
    std::string args, needle;
  };
  const Case cases[] = {
      {"--cell " + two, "the plan is for 3 fingers"},
      {"--cell " + kCellsDir + "default.yaml --trials 0", "--trials"},
      {"--cell " + kCellsDir + "default.yaml --trials 1.5", "--trials"},
      {"--cell " + kCellsDir + "default.yaml --trial-batch 0", "--trial-batch"},
      {"--cell " + kCellsDir + "default.yaml --max-trials 100001", "--max-trials"},
      {"--cell " + kCellsDir + "default.yaml --trial-batch 128 --max-trials 64", "--max-trials"},
      {"--cell " + kCellsDir + "default.yaml --trial-batch 1024", "--trial-batch"},
      {"--cell " + kCellsDir + "default.yaml --trials 8 --max-trials 64", "--max-trials"},
      {"--cell " + kCellsDir + "default.yaml --trials 8 --trial-batch 4", "--trial-batch"},
      {"--cell " + kCellsDir + "default.yaml --confidence 1", "--confidence"},
      {"--cell " + kCellsDir + "default.yaml --confidence 0.2", "--confidence"},
      {"--cell " + kCellsDir + "default.yaml --required-rate 1.01", "--required-rate"},
      {"--cell " + kCellsDir + "default.yaml --required-rate x", "--required-rate"},
      {"--cell " + kCellsDir + "default.yaml --seed -2", "--seed"},
      {"--cell /nonexistent.yaml", "/nonexistent.yaml"},
  };
  for (const Case& c : cases) {
    const std::string out = writeTemp("never_replay.json", "");
    std::remove(out.c_str());
    const Result r = run(base + c.args + " --out " + out);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(std::ifstream(out).good()) << c.args;
  }
  // The plan itself may not be overwritten.
  const Result self = run(base + "--cell " + kCellsDir + "default.yaml --out " + smallPlan());
  EXPECT_EQ(self.status, 2) << self.err;
  EXPECT_TRUE(nlohmann::json::parse(slurp(smallPlan())).contains("certificate"));
}

}  // namespace
}  // namespace rbsf::cli_test
