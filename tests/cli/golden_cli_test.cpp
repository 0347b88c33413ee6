// plan-reorientation's files, report and standard output (less the planning time) are
// byte-identical to those recorded in tests/cli/golden/plans.sha256, for fixed seeds with
// --reproducible: a refactoring that moves code must not change a plan. The runs do not
// optimise: the optimiser's BLAS (OpenBLAS) picks its kernels by CPU, so its last bits
// depend on the machine.
//
// A change that is meant to change plans updates the file: run this test, check that the
// change in the plans is the intended one, and paste the hashes the failures print.
#include <gtest/gtest.h>
#include <unistd.h>

#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "cli_support.h"

namespace {

using namespace rbsf::cli_test;

const std::string kPlanExe = RBSF_PLAN_EXE;
const std::string kCells = std::string(RBSF_SOURCE_DIR) + "/cells/";
const std::string kHashes = std::string(RBSF_SOURCE_DIR) + "/tests/cli/golden/plans.sha256";

/// name -> hash, from lines "<sha256>  <name>" ('#' starts a comment).
std::map<std::string, std::string> recorded() {
  std::map<std::string, std::string> out;
  std::istringstream in(slurp(kHashes));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string hash, name;
    if (fields >> hash >> name) out[name] = hash;
  }
  return out;
}

std::string sha256(const std::string& path) {
  const Result r = run("sha256sum " + path);
  return r.status == 0 ? r.out.substr(0, r.out.find(' ')) : "(sha256sum failed)";
}

/// Run plan-reorientation with `args` plus every output, and compare each output and the
/// standard output with the recorded hashes of `tag`.
void expectRecorded(const std::string& tag, const std::string& args, int expected_status) {
  const std::string base = ::testing::TempDir() + std::to_string(getpid()) + "_golden_" + tag;
  // From the cells folder with a relative cell path: the pictures name the cell as given,
  // and a checkout's own path must not change them.
  const Result r =
      run("cd " + kCells + " && " + kPlanExe + " " + args + " --reproducible --out " + base +
          ".json --csv " + base + ".csv --svg " + base + ".svg --report " + base + ".html");
  ASSERT_EQ(r.status, expected_status) << r.err;
  // The standard output less its one wall-clock figure, the planning time.
  const std::string text =
      std::regex_replace(r.out, std::regex("planned in [0-9.]+ s"), "planned in");
  const std::string stdout_file = writeTemp("golden_" + tag + ".stdout", text);
  const auto hashes = recorded();
  ASSERT_FALSE(hashes.empty()) << "no hashes in " << kHashes;
  const std::pair<std::string, std::string> outputs[] = {{tag + ".json", base + ".json"},
                                                         {tag + ".csv", base + ".csv"},
                                                         {tag + ".svg", base + ".svg"},
                                                         {tag + ".html", base + ".html"},
                                                         {tag + ".stdout", stdout_file}};
  for (const auto& [name, path] : outputs) {
    const auto it = hashes.find(name);
    ASSERT_NE(it, hashes.end()) << name << " has no recorded hash in " << kHashes;
    EXPECT_EQ(sha256(path), it->second) << name << " differs from the recorded file";
  }
}

TEST(GoldenPlans, SupportPlanIsByteIdenticalToTheRecordedOne) {
  // The support planner on the default cell: the 30 degree support plan (its contacts' roles
  // per segment) and its default, sequential certificate, 64 of 64: certified, exit 0. Not
  // optimised, as the file comment says.
  expectRecorded("support30",
                 "--cell default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-30deg --quiet"
                 " --planner support --no-optimize",
                 0);
}

TEST(GoldenPlans, KinodynamicPlanIsByteIdenticalToTheRecordedOne) {
  // One KPIECE1 search with a fixed seed and a budget in propagations (it ends at the goal
  // well within it), not optimised; the plan is not certified (exit 4).
  expectRecorded("kpiece15",
                 "--cell default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --seed 1"
                 " --time-limit 3600 --max-propagations 200000 --quiet --planner KPIECE1"
                 " --attempts 1 --no-optimize --trials 8",
                 4);
}

}  // namespace
