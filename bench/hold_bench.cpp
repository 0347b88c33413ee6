// Holding benchmark (a program, not a timed test): the part held at rest where it is placed
// (planner/hold_plan.h: the contact set that holds it best, the others lifted), certified with
// a fixed number of closed-loop trials (default 256, seed 1) under the part-feedback law (the
// cell's sensing) and under the joint law (the same cell with part_pose: none), the same
// draws for both. One line per law: successes, the bound, the worst trial.
//   build/bench/rbsf_hold_bench [--cell cells/default.yaml] [--pose 0.1,0.40,0]
//                               [--trials 256] [--trial-seed 1] [--duration 3]
#include <chrono>
#include <cstdio>
#include <string>

#include "rbsf/dynamics/cell.h"
#include "rbsf/dynamics/placement.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/planner/hold_plan.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/tool_main.h"

namespace {

int run(int argc, char** argv) {
  std::string cell_path = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";
  std::string pose_text = "0.1,0.40,0";
  int trials = 256, seed = 1;
  double duration = 3.0;
  CLI::App app{
      "Holding benchmark: the part held at rest on its best contact set, certified "
      "under part feedback and joint feedback with a fixed number of trials.",
      "rbsf_hold_bench"};
  app.footer(rbsf::tools::kExitStatusHelp);
  app.add_option("--cell", cell_path, "cell file (default cells/default.yaml)");
  app.add_option("--pose", pose_text, "the part's pose x,y,phi (default 0.1,0.40,0)");
  app.add_option("--trials", trials, "trials per law (default 256)")->check(CLI::Range(1, 100000));
  app.add_option("--trial-seed", seed, "seed of the draws (default 1)")
      ->check(CLI::Range(1, 1 << 30));
  app.add_option("--duration", duration, "the rest [s] (default 3)")->check(CLI::Range(0.5, 600.0));
  rbsf::tools::parseCommandLine(app, argc, argv);

  const rbsf::Cell cell = rbsf::loadCell(cell_path);
  rbsf::Cell blind = cell;
  blind.sensing.part_pose.present = false;
  const rbsf::RbsfModel model(cell), joints_only(blind);
  const rbsf::Pose pose = rbsf::tools::parsePose(pose_text, "--pose");
  const rbsf::VecQ q0 = rbsf::restingConfiguration(model, pose, 0.0);
  rbsf::planner::HoldSettings hs;
  hs.duration = duration;
  rbsf::plan::Plan plan = rbsf::planner::holdPlan(model, q0, hs);
  plan.joint_feedback = false;  // the law the cell's sensing allows
  std::printf("hold plan: %.1f s on fingers", duration);
  for (int i = 0; i < model.numFingers(); ++i)
    if (plan.segments.front().contacts[i] == rbsf::ContactRole::kStick) std::printf(" %d", i + 1);
  std::printf(" (the others lifted), %d trials, seed %d\n", trials, seed);
  rbsf::plan::CertificateSettings settings;
  settings.trials = trials;
  settings.seed = static_cast<std::uint64_t>(seed);
  for (const bool part : {true, false}) {
    const auto t0 = std::chrono::steady_clock::now();
    const rbsf::plan::Certificate c =
        rbsf::plan::certify(part ? model : joints_only, plan, settings);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-14s %d/%d held (bound %.3f), %.1f s; worst: %s\n",
                part ? "part feedback" : "joints only", c.successes, c.trials, c.lower_bound, wall,
                c.worst.success ? "succeeded" : c.worst.failure.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf_hold_bench", argc, argv, run);
}
