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
