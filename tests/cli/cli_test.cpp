// The command-line tools as a user runs them: exit status, messages, JSON output.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct Result {
  int status = -1;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

/// Run a shell command line, capturing stdout and stderr separately.
Result run(const std::string& args) {
  static int counter = 0;
  const std::string base = ::testing::TempDir() + "rbsf_cli_" + std::to_string(getpid()) + "_" +
                           std::to_string(counter++);
  const std::string cmd = args + " >" + base + ".out 2>" + base + ".err";
  const int raw = std::system(cmd.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(base + ".out");
  r.err = slurp(base + ".err");
  return r;
}

const std::string kAnalyze = RBSF_ANALYZE_EXE;
const std::string kCells = std::string(RBSF_SOURCE_DIR) + "/cells/";

std::string writeTemp(const std::string& name, const std::string& text) {
  // ctest runs each case in its own process, in parallel: names carry the pid.
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Analyze, JsonHasEveryKeyForTheDefaultRestingPose) {
  const Result r = run(kAnalyze + " --cell " + kCells + "default.yaml --pose 0.1,0.40,0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["contacts"].size(), 3u);
  for (const auto& c : j["contacts"]) {
    for (const char* key : {"xi", "gap", "f_n", "delta_n", "alpha_t", "alpha_n"})
      EXPECT_TRUE(c[key].is_number()) << key;
    EXPECT_EQ(c["normal"].size(), 2u);
    EXPECT_LT(std::abs(c["gap"].get<double>()), 1e-6);
  }
  EXPECT_EQ(j["accel"].size(), 7u);
  EXPECT_TRUE(j["sigma_min"].is_number());
  EXPECT_TRUE(j["determinate"].get<bool>());
  EXPECT_TRUE(j["phase_c_feasible"].is_boolean());
  EXPECT_TRUE(j["omega_dot_signs"].is_array());
  // The default part rests on three fingers and can be held.
  ASSERT_TRUE(j["holding_tau"].is_array());
  EXPECT_EQ(j["holding_tau"].size(), 4u);
}

TEST(Analyze, PoseAndExplicitConfigurationAgree) {
  // --pose with degrees and --name=value forms, then the configuration it placed given
  // back as --q in radians: both paths must analyse the same state.
  const Result a = run(kAnalyze + " --cell " + kCells + "default.yaml --pose=0.12,0.41,10deg" +
                       " --theta -5deg --json");
  ASSERT_EQ(a.status, 0) << a.err;
  const auto ja = nlohmann::json::parse(a.out);
  ASSERT_EQ(ja["q"].size(), 7u);
  EXPECT_NEAR(ja["q"][2].get<double>(), 10 * M_PI / 180, 1e-12);
  EXPECT_NEAR(ja["q"][3].get<double>(), -5 * M_PI / 180, 1e-12);
  std::string q;
  for (const auto& x : ja["q"]) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x.get<double>());
    if (!q.empty()) q += ',';
    q += buf;
  }
  const Result b = run(kAnalyze + " --cell " + kCells + "default.yaml --q " + q + " --json");
  ASSERT_EQ(b.status, 0) << b.err;
  const auto jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(jb["q"], ja["q"]);
  EXPECT_EQ(jb["holding_tau"], ja["holding_tau"]);
  EXPECT_EQ(jb["accel"], ja["accel"]);
}

TEST(Analyze, TableIsTheDefault) {
  const Result r = run(kAnalyze + " --cell " + kCells + "default.yaml --pose 0.1,0.40,0");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("holding tau"), std::string::npos);
  EXPECT_NE(r.out.find("sigma_min"), std::string::npos);
}

struct BadCase {
  const char* name;
  std::string args;
  const char* message;  // must appear in stderr
};

class AnalyzeBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(AnalyzeBadInput, ExitsWithStatus2AndNamesTheCulprit) {
  const Result r = run(kAnalyze + " " + GetParam().args);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << "no partial output: " << r.out;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one message: " << r.err;
}

std::vector<BadCase> badCases() {
  const std::string cell = "--cell " + kCells + "default.yaml";
  const std::string neg_mass = writeTemp("neg_mass.yaml", slurp(kCells + "default.yaml"));
  {
    std::string t = slurp(kCells + "default.yaml");
    t.replace(t.find("mass: 24.0"), 10, "mass: -24.0");
    std::ofstream(neg_mass) << t;
  }
  const std::string no_fingers =
      writeTemp("no_fingers.yaml",
                "base: {inertia: 5.0, theta_limits: [-0.7, 0.7], torque_limit: 300.0}\n"
                "fingers: []\n"
                "object: {shape: {type: circle, radius: 0.1}, mass: 5.0, inertia: 0.1}\n"
                "friction: {static: 0.5}\n");
  const std::string malformed = writeTemp("malformed.yaml", "base: {inertia: [1,\n");
  return {
      {"missing_file", "--cell /nonexistent.yaml --pose 0.1,0.4,0", "/nonexistent.yaml"},
      {"malformed_yaml", "--cell " + malformed + " --pose 0.1,0.4,0", "malformed.yaml"},
      {"negative_mass", "--cell " + neg_mass + " --pose 0.1,0.4,0", "object.mass"},
      {"zero_fingers", "--cell " + no_fingers + " --pose 0.1,0.4,0", "fingers"},
      {"non_numeric_v", cell + " --pose 0.1,0.4,0 --v 0,0,abc,0,0,0,0", "--v"},
      {"short_tau", cell + " --pose 0.1,0.4,0 --tau 1,2", "--tau"},
      {"short_q", cell + " --q 0,0.4,0,0", "--q"},
      {"bad_angle", cell + " --pose 0,0.4,30degrees", "--pose"},
      {"off_boundary", cell + " --q 0,0.4,0,0,0.30,0.25,0.30", "finger 1"},
      {"unreachable", cell + " --pose 0.1,1.4,0", "finger 1"},
      {"no_state", cell, "--q or --pose"},
      {"unknown_option", cell + " --pose 0.1,0.4,0 --frobnicate 1", "frobnicate"},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, AnalyzeBadInput, ::testing::ValuesIn(badCases()),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace

// ---- plan-reorientation ----
const std::string kPlan = RBSF_PLAN_EXE;

TEST(PlanReorientation, SolvesASmallProblemAndWritesJsonAndCsv) {
  const std::string out = writeTemp("plan.json", ""), csv = writeTemp("plan.csv", "");
  const Result r = run(kPlan + " --cell " + kCells +
                       "default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --seed 7"
                       " --time-limit 120 --quiet --out " +
                       out + " --csv " + csv);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // --quiet, and not a terminal anyway
  const auto j = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(j["status"], "exact");
  EXPECT_TRUE(j["planning_time"].is_number());
  EXPECT_TRUE(j["propagations"].is_number_integer());
  ASSERT_FALSE(j["segments"].empty());
  for (const auto& s : j["segments"]) {
    const std::string ph = s["phase"];
    EXPECT_TRUE(ph == "C" || ph == "P" || ph == "U") << ph;
    EXPECT_GT(s["duration"].get<double>(), 0.0);
    EXPECT_EQ(s["tau"].size(), 4u);
  }
  ASSERT_FALSE(j["samples"].empty());
  for (const char* key : {"t", "q", "v", "tau", "f_n", "phase"})
    EXPECT_TRUE(j["samples"][0].contains(key)) << key;
  EXPECT_EQ(j["samples"][0]["f_n"].size(), 3u);
  const std::string text = slurp(csv);
  EXPECT_EQ(text.rfind("t,x,y,phi,theta,l1,l2,l3,dx,", 0), 0u);
  EXPECT_EQ(static_cast<size_t>(std::count(text.begin(), text.end(), '\n')),
            j["samples"].size() + 1);
}

TEST(PlanReorientation, TimeLimitWithoutExactPlanExitsThree) {
  const std::string out = writeTemp("approx.json", "");
  const Result r = run(kPlan + " --cell " + kCells +
                       "default.yaml --start 0.1,0.40,0 --goal=-0.1,0.40,180deg --seed 1"
                       " --time-limit 0.05 --quiet --out " +
                       out);
  ASSERT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.out.find("best distance"), std::string::npos) << r.out;
}

TEST(PlanReorientation, BadInputIsRefusedWithExitTwo) {
  const std::string base = kPlan + " --cell " + kCells + "default.yaml --quiet ";
  struct Case {
    std::string args, needle;
  };
  const Case cases[] = {
      {"--start 0.1,2.0,0 --goal 0.1,0.4,10deg", "cannot hold the start pose"},
      {"--start 0.1,0.40,0 --goal 0.1,3.0,0", "out of reach: no finger"},
      {"--start 0.1,0.40,0 --goal 0.1,0.4,abc", "--goal"},
      {"--start 0.1,0.40,0 --goal 0.1,0.4,0 --planner PRM", "unknown planner 'PRM'"},
      {"--start 0.1,0.40,0 --goal 0.1,0.4,0 --time-limit -1", "--time-limit"},
      {"--start 0.1,0.40,0 --goal 0.1,0.4,0 --seed 1.5", "--seed"},
      {"--start 0.1,0.40 --goal 0.1,0.4,0", "--start"},
  };
  for (const Case& c : cases) {
    const std::string out = writeTemp("never.json", "");
    std::remove(out.c_str());
    const Result r = run(base + c.args + " --out " + out);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
    EXPECT_FALSE(std::ifstream(out).good()) << c.args << ": wrote a file";
  }
}
