// The tools' contract with the file system and the shell: an output never replaces an
// input, another output or something that is not a regular file; every output is checked
// before any work; inputs are regular files under a size cap; runs are bounded; bad values
// exit 2 with one message naming them; SIGTERM stops a run like SIGINT (143).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "cli_support.h"

namespace {

using namespace rbsf::cli_test;
using Clock = std::chrono::steady_clock;

const std::string kPlan = RBSF_PLAN_EXE;
const std::string kSimulate = RBSF_SIMULATE_EXE;
const std::string kAnalyze = RBSF_ANALYZE_EXE;
const std::string kCells = std::string(RBSF_SOURCE_DIR) + "/cells/";
// A 15 degree problem the planner solves in about a second.
const std::string kSmallPlan = kPlan + " --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --quiet";

/// A fresh directory for one test.
std::string tempDir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + std::to_string(getpid()) + "_" + name;
  std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
  return dir;
}

bool isRegular(const std::string& path) {
  struct stat st;
  return ::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

TEST(OutputFiles, AnOutputNamingTheCellIsRefusedAndTheCellKept) {
  const std::string dir = tempDir("out_is_cell");
  const std::string cell = dir + "/c.yaml";
  std::system(("cp " + kCells + "default.yaml " + cell).c_str());
  const std::string before = slurp(cell);
  for (const std::string& alias : {cell, dir + "/./c.yaml", dir + "//c.yaml"}) {
    const Result r = run(kSmallPlan + " --cell " + cell + " --out " + alias);
    EXPECT_EQ(r.status, 2) << alias << "\n" << r.err;
    EXPECT_NE(r.err.find("is the input given to --cell"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(cell), before);
  }
}

TEST(OutputFiles, AnOutputThatIsTheCellByAnotherNameIsRefusedAndTheCellKept) {
  // Names the path comparison cannot tell apart; only the file's identity (device and inode)
  // can: a hard link to the cell as the output, and the cell given through a symbolic link
  // with the file itself as the output.
  const std::string dir = tempDir("out_is_cell_linked");
  const std::string cell = dir + "/c.yaml";
  std::system(("cp " + kCells + "default.yaml " + cell + " && ln " + cell + " " + dir +
               "/hard.json && ln -s c.yaml " + dir + "/soft.yaml")
                  .c_str());
  const std::string before = slurp(cell);
  for (const auto& [input, output] :
       {std::pair{cell, dir + "/hard.json"}, std::pair{dir + "/soft.yaml", cell}}) {
    const Result r = run(kSmallPlan + " --cell " + input + " --out " + output);
    EXPECT_EQ(r.status, 2) << input << " -> " << output << "\n" << r.err;
    EXPECT_NE(r.err.find("is the input given to --cell"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(cell), before);
  }
}

TEST(OutputFiles, SimulateRefusesToWriteOverItsControls) {
  const std::string dir = tempDir("out_is_controls");
  const std::string controls = dir + "/controls.csv";
  std::system(("cp " + kCells + "default_controls.csv " + controls).c_str());
  const std::string before = slurp(controls);
  const Result r =
      run(kSimulate + " --cell " + kCells + "default.yaml --start 0.1,0.40,0" + " --controls " +
          controls + " --out " + dir + "/../" + dir.substr(dir.rfind('/') + 1) + "/controls.csv");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("is the input given to --controls"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(controls), before);
}

TEST(OutputFiles, TwoSpellingsOrALinkOfOneOutputAreOneFile) {
  const std::string dir = tempDir("same_output");
  std::system(("mkdir -p " + dir + "/o && ln -s o " + dir + "/link").c_str());
  const std::string base =
      kSmallPlan + " --cell " + kCells + "default.yaml --out " + dir + "/o/same.json";
  for (const std::string& other : {dir + "/o/./same.json", dir + "/link/same.json"}) {
    const Result r = run(base + " --csv " + other);
    EXPECT_EQ(r.status, 2) << other << "\n" << r.err;
    EXPECT_NE(r.err.find("is also given to --out"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(isRegular(dir + "/o/same.json"));  // refused before any work: nothing written
}

TEST(OutputFiles, DevicesFifosAndLinksAreNeverReplaced) {
  const std::string dir = tempDir("special");
  const std::string fifo = dir + "/fifo.json", link = dir + "/link.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::system(("echo keep > " + dir + "/target.json && ln -s target.json " + link).c_str());
  for (const std::string& out : {std::string("/dev/null"), fifo, link}) {
    const Result r = run(kSmallPlan + " --cell " + kCells + "default.yaml --out " + out);
    EXPECT_EQ(r.status, 2) << out << "\n" << r.err;
    EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
  }
  struct stat st;
  ASSERT_EQ(::lstat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  ASSERT_EQ(::lstat(link.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(slurp(dir + "/target.json"), "keep\n");
}

TEST(OutputFiles, AnUnwritablePlaceIsRefusedBeforeAnyPlanning) {
  // /proc takes no new file whoever runs the test (root included).
  const Clock::time_point t0 = Clock::now();
  const Result r = run(kPlan + " --cell " + kCells +
                       "default.yaml --start 0.1,0.40,0 --goal=-0.1,0.40,180deg --quiet --out "
                       "/proc/rbsf_plan.json");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--out: cannot write '/proc/rbsf_plan.json': cannot create a file"),
            std::string::npos)
      << r.err;
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 3.0);
}

TEST(InputFiles, ADeviceADirectoryOrAHugeFileIsRefusedAtOnce) {
  const std::string dir = tempDir("inputs");
  const std::string huge = dir + "/huge.yaml";
  std::system(("truncate -s 65M " + huge).c_str());
  struct Case {
    std::string cell, needle;
  };
  for (const Case& c : {Case{"/dev/zero", "not a regular file"}, Case{dir, "it is a directory"},
                        Case{huge, "68157440 bytes, more than the limit of 67108864"}}) {
    const Clock::time_point t0 = Clock::now();
    const Result r = run(kSmallPlan + " --cell " + c.cell);
    EXPECT_EQ(r.status, 2) << c.cell << "\n" << r.err;
    EXPECT_NE(r.err.find("cannot read the cell file: " + c.needle), std::string::npos) << r.err;
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 3.0) << c.cell;
  }
  const Result r = run(kSimulate + " --cell " + kCells + "default.yaml --start 0.1,0.40,0" +
                       " --controls " + dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("cannot read the controls file: it is a directory"), std::string::npos)
      << r.err;
}

TEST(Bounds, SimulateRefusesRunsBeyondItsStepAndOutputLimits) {
  const std::string base =
      kSimulate + " --cell " + kCells + "default.yaml --start 0.1,0.40,0 --controls ";
  const std::string dir = tempDir("bounds");
  const std::string long_run = writeTemp("long_controls.csv",
                                         "duration,tau_theta,tau_1,tau_2,tau_3\n"
                                         "1e9,0,80,80,80\n");
  const std::string second = writeTemp("second_controls.csv",
                                       "duration,tau_theta,tau_1,tau_2,tau_3\n"
                                       "1,0,80,80,80\n");
  const std::string short_step = writeTemp("short_controls.csv",
                                           "duration,tau_theta,tau_1,tau_2,tau_3\n"
                                           "0.0004,0,80,80,80\n");
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : {Case{long_run, "more than 10000000 steps"},
                        Case{second + " --dt 1e-9", "more than 10000000 steps"},
                        Case{second + " --dt 1e-300", "steps of 1e-300 s"},
                        Case{short_step, "0.0004 s is shorter than the time step 0.001 s"},
                        Case{second + " --dt 5e-7 --out " + dir + "/t.csv",
                             "--out: the run takes 2000000 steps, a sample each; at most "
                             "1000000 are written"}}) {
    const Clock::time_point t0 = Clock::now();
    const Result r = run(base + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 3.0) << c.args;
  }
  EXPECT_FALSE(isRegular(dir + "/t.csv"));
}

TEST(Bounds, APartThatFallsOffEndsTheSimulationWithAWarning) {
  // The base swung to its limit and the fingers pulled down: the part leaves the fingers.
  // The run stops 1 m below the start instead of writing kilometres of free fall.
  const std::string controls = writeTemp("fall_controls.csv",
                                         "duration,tau_theta,tau_1,tau_2,tau_3\n"
                                         "30,200,-50,-50,-50\n");
  const std::string csv = tempDir("fall") + "/fall.csv";
  const Result r = run(kSimulate + " --cell " + kCells + "default.yaml --start 0.1,0.40,0" +
                       " --controls " + controls + " --out " + csv);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the part fell off the fingers"), std::string::npos) << r.err;
  const std::string text = slurp(csv);
  const std::string last = text.substr(text.rfind('\n', text.size() - 2) + 1);
  const double t = std::stod(last),
               y = std::stod(last.substr(last.find(',', last.find(',') + 1) + 1));
  EXPECT_LT(t, 5.0) << last;
  EXPECT_GT(y, 0.40 - 1.2) << last;  // stopped about 1 m below the start
}

TEST(ExitStatus, AnalysisInputsAreCheckedLikeSimulationInputs) {
  const std::string base = kAnalyze + " --cell " + kCells + "default.yaml --pose 0.1,0.40,0 ";
  struct Case {
    std::string args, needle;
  };
  for (const Case& c :
       {Case{"--v 1e200,0,0,0,0,0,0", "'1e200' is beyond 100 (m/s or rad/s)"},
        Case{"--v 0,0,1e5,0,0,0,0", "is beyond 100"},
        Case{"--tau 0,1e6,0,0", "--tau: 'tau_1': 1e+06 N exceeds finger 1's force limit"},
        Case{"--tau 1e9,0,0,0", "'tau_theta'"}}) {
    const Result r = run(base + c.args + " --json");
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  }
}

TEST(ExitStatus, AnAbsurdGoalAngleIsBadInput) {
  const Result r = run(kPlan + " --cell " + kCells +
                       "default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,1e20deg --quiet");
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--goal"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("36000 deg"), std::string::npos) << r.err;
}

TEST(ExitStatus, SigtermStopsAPlanLikeSigintWithStatus143) {
  const std::string dir = tempDir("sigterm");
  const std::string out = dir + "/p.json";
  const Stopped r = runAndSignal({kPlan, "--cell", kCells + "default.yaml", "--start", "0.1,0.40,0",
                                  "--goal", "0.3,0.40,90deg", "--time-limit", "600", "--planner",
                                  "KPIECE1", "--quiet", "--no-optimize", "--out", out},
                                 SIGTERM, std::chrono::milliseconds(1500));
  EXPECT_EQ(r.status, 143);
  const auto plan = nlohmann::json::parse(slurp(out));  // the best plan so far, complete
  EXPECT_EQ(plan["status"], "approximate");
}

TEST(ExitStatus, SigtermStopsASimulationWithStatus143AndNoFile) {
  const std::string controls = writeTemp("long_hold.csv",
                                         "duration,tau_theta,tau_1,tau_2,tau_3\n"
                                         "9,23.544,39.8447,98.0387,156.417\n");
  const std::string out = tempDir("sim_sigterm") + "/long.csv";
  const Stopped r =
      runAndSignal({kSimulate, "--cell", kCells + "default.yaml", "--start", "0.1,0.40,0",
                    "--controls", controls, "--dt", "1e-5", "--out", out},
                   SIGTERM, std::chrono::milliseconds(500));
  EXPECT_EQ(r.status, 143);
  const pid_t pid = r.pid;
  EXPECT_FALSE(isRegular(out));
  EXPECT_FALSE(isRegular(out + ".tmp." + std::to_string(pid)));  // the streamed file removed
}

TEST(Progress, WithoutATerminalEachStageIsALine) {
  // 2 of 2 trials bound the rate at 0.22: the support plan certifies, one stage each.
  const Result r = run(kPlan + " --cell " + kCells +
                       "default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --trials 2 "
                       "--required-rate 0.2");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("plan-reorientation: searching supports\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("plan-reorientation: optimising and certifying the support plan\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  const Result quiet = run(kPlan + " --cell " + kCells +
                           "default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --trials 2 "
                           "--required-rate 0.2 --quiet");
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

}  // namespace
