// Output files are complete or absent; SIGINT is a stop request; plan files parse from text
// and leave wall-clock fields out on request.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/tools/interrupt.h"

namespace rbsf::tools {
namespace {

bool exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

TEST(AtomicFile, WritesTheWholeTextAndLeavesNoTemporary) {
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_atomic.txt";
  writeFileAtomically(path, "first\n", "--out");
  writeFileAtomically(path, std::string(100000, 'x'), "--out");
  EXPECT_EQ(slurp(path), std::string(100000, 'x'));
  EXPECT_FALSE(exists(temporaryPathFor(path)));
  std::remove(path.c_str());
}

TEST(AtomicFile, FailureLeavesNoFileAndNamesThePath) {
  const std::string path = ::testing::TempDir() + "no_such_dir_rbsf/out.svg";
  try {
    writeFileAtomically(path, "text", "--svg");
    FAIL() << "written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--svg: cannot write '" + path + "'"), std::string::npos);
  }
  EXPECT_FALSE(exists(path));
  EXPECT_FALSE(exists(temporaryPathFor(path)));
  // A directory in the way of the rename: the old entry stays, the temporary is removed.
  const std::string dir = ::testing::TempDir() + std::to_string(getpid()) + "_a_dir";
  ::mkdir(dir.c_str(), 0755);
  EXPECT_THROW(writeFileAtomically(dir, "text", "--out"), InputError);
  EXPECT_FALSE(exists(temporaryPathFor(dir)));
  ::rmdir(dir.c_str());
}

TEST(AtomicFile, CheckWritableRefusesMissingDirectoriesAndDirectories) {
  EXPECT_THROW(checkWritable("/nonexistent_rbsf_dir/plan.json", "--out"), InputError);
  EXPECT_THROW(checkWritable(::testing::TempDir(), "--out"), InputError);
  EXPECT_THROW(checkWritable("", "--out"), InputError);
  EXPECT_NO_THROW(checkWritable(::testing::TempDir() + "fresh_name.json", "--out"));
  EXPECT_NO_THROW(checkWritable("relative_name.json", "--out"));
}

TEST(Interrupt, FirstSigintSetsTheFlagAndTheProcessGoesOn) {
  const std::atomic<bool>& flag = InterruptFlag::install();
  InterruptFlag::reset();
  EXPECT_FALSE(flag.load());
  ASSERT_EQ(::raise(SIGINT), 0);
  EXPECT_TRUE(flag.load());
  EXPECT_TRUE(InterruptFlag::raised());
  InterruptFlag::reset();
  EXPECT_FALSE(InterruptFlag::raised());
}

TEST(InterruptDeathTest, SecondSigintExitsAtOnceWithStatus130) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        InterruptFlag::install();
        InterruptFlag::reset();
        ::raise(SIGINT);
        ::raise(SIGINT);
        std::fprintf(stderr, "still running\n");
        std::exit(0);
      },
      ::testing::ExitedWithCode(kExitInterrupted), "^$");
}

plan::Plan tinyPlan() {
  plan::Plan p;
  p.status = plan::PlanStatus::kApproximate;
  p.planner = "KPIECE1";
  p.seed = 3;
  p.planning_time = 1.25;
  p.q0 = VecQ::Zero(7);
  p.q0[1] = 0.4;
  plan::PlanSegment s;
  s.steps = 20, s.duration = 0.02, s.tau = VecU::Constant(4, 1.5);
  p.segments.push_back(s);
  plan::PlanSample a;
  a.t = 0.0, a.q = p.q0, a.v = VecQ::Zero(7), a.tau = s.tau, a.f_n = VecC::Constant(3, 2.0);
  p.samples.push_back(a);
  return p;
}

TEST(PlanFile, ReproducibleTextLeavesPlanningTimeOutAndStillParses) {
  const plan::Plan p = tinyPlan();
  const std::string full = plan::planJsonText({p, {}, {}});
  EXPECT_NE(full.find("\"planning_time\""), std::string::npos);
  plan::PlanFileOptions o;
  o.wall_clock = false;
  const std::string repro = plan::planJsonText({p, {}, {}}, o);
  EXPECT_EQ(repro.find("planning_time"), std::string::npos);
  const plan::Plan back = plan::parsePlanJson(repro, "<text>").plan;
  EXPECT_EQ(back.planning_time, 0.0);
  EXPECT_EQ(back.seed, 3u);
  EXPECT_TRUE(back.samples.front().f_n == p.samples.front().f_n);
  EXPECT_EQ(plan::parsePlanJson(full, "<text>").plan.planning_time, 1.25);
  // Text and file readers agree.
  EXPECT_EQ(plan::planJsonText({back, {}, {}}, o), repro);
}

TEST(PlanFile, OutOfRangeIntegersAndNonFiniteNumbersAreInputErrors) {
  // Found with tests/fuzz/fuzz_plan.cpp under UBSan: a float or out-of-range value was cast to
  // int / uint32 / uint64 (undefined behaviour), a negative seed wrapped around; a zero step
  // count or time step was accepted; an over-long array overran a fixed-capacity vector.
  const nlohmann::json good = nlohmann::json::parse(plan::planJsonText({tinyPlan(), {}, {}}));
  ASSERT_NO_THROW(plan::parsePlanJson(good.dump(), "<good>"));
  struct Case {
    std::string edit, needle;
  };
  auto with = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = good;
    edit(j);
    return j.dump();
  };
  const std::pair<std::string, std::string> cases[] = {
      {with([](auto& j) { j["segments"][0]["steps"] = 1e30; }),
       "segments[].steps must be an integer"},
      {with([](auto& j) { j["segments"][0]["steps"] = 0; }), "segments[].steps must be an integer"},
      {with([](auto& j) { j["seed"] = 1e20; }), "seed must be an integer"},
      {with([](auto& j) { j["seed"] = -5; }), "seed must be an integer"},
      {with([](auto& j) { j["propagations"] = 1e30; }), "propagations must be an integer"},
      {with([](auto& j) { j["steps_per_control"] = 2.5; }), "steps_per_control must be an integer"},
      {with([](auto& j) { j["time_step"] = 0.0; }), "time_step must be positive"},
      // Longer than the inline capacity of VecQ / VecC: overran Eigen's storage in Release.
      {with([](auto& j) { j["samples"][0]["q"] = std::vector<double>(17, 0.0); }),
       "samples[].q has 17 entries; at most 16"},
      {with([](auto& j) { j["samples"][0]["f_n"] = std::vector<double>(13, 1.0); }),
       "samples[].f_n has 13 entries; at most 12"},
      {with([](auto& j) { j["q0"] = std::vector<double>(40, 0.0); }), "q0 has 40 entries"},
      {[&] {
         std::string t = good.dump();
         const std::string key = "\"goal_distance\":0.0";
         return t.replace(t.find(key), key.size(), "\"goal_distance\":1e400");
       }(),
       "number overflow"},  // refused by the JSON parser itself
  };
  for (const auto& [text, needle] : cases) {
    try {
      plan::parsePlanJson(text, "<case>");
      ADD_FAILURE() << "accepted: " << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace rbsf::tools
