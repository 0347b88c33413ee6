// Holding benchmark (a program, not a timed test): the part held at rest where it is placed
// (planner/hold_plan.h: the contact set that holds it best, the others lifted), certified with
// a fixed number of closed-loop trials (default 256, seed 1) under the part-feedback law (the
// cell's sensing) and under the joint law (the same cell with part_pose: none), the same
// draws for both. One line per law: successes, the bound, the worst trial.
//   build/bench/rbsf_hold_bench [--cell cells/default.yaml] [--pose 0.1,0.40,0]
//                               [--trials 256] [--trial-seed 1] [--duration 3]
//                               [--list-failures] [--friction-use U] [--margin-reward C]
// --friction-use, --margin-reward: the law's ContactForceSettings (contact_force_qp.h).
// --list-failures: each failed trial's draw (mu_s, mu_k, mass, COM offset, start offset).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/plan/trial.h"
#include "rbsf/planner/support/hold_plan.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/tool_main.h"

namespace {

/// Every failed trial of `settings` on `model` (the certificate's draws, run again one by
/// one): the drawn friction, mass, COM offset and start offset.
void listFailures(const rbsf::RbsfModel& model, const rbsf::plan::Plan& plan,
                  const rbsf::plan::CertificateSettings& settings) {
  namespace layout = rbsf::layout;
  const rbsf::FeedbackSchedule schedule(model, rbsf::plan::makeReference(plan),
                                        rbsf::plan::lawSensing(model.cell().sensing, plan),
                                        plan.simulator);
  for (int i = 0; i < settings.trials; ++i) {
    const rbsf::plan::TrialDraw d = rbsf::plan::drawTrial(model.cell(), plan, settings.seed, i);
    const rbsf::plan::TrialOutcome o =
        rbsf::plan::runTrial(schedule, plan, d, settings.trial, false);
    if (o.success) continue;
    std::printf(
        "  trial %d: mu_s %.3f mu_k %.3f mass %.2f kg, COM (%+.4f, %+.4f) m, start "
        "(%+.4f m, %+.4f m, %+.3f deg) off; %s\n",
        i, d.cell.friction.mu_static, d.cell.friction.mu_kinetic, d.cell.object.mass,
        d.com_offset.x(), d.com_offset.y(), d.q0[layout::kX] - plan.q0[layout::kX],
        d.q0[layout::kY] - plan.q0[layout::kY],
        (d.q0[layout::kPhi] - plan.q0[layout::kPhi]) * 180 / M_PI, o.failure.c_str());
  }
}

int run(int argc, char** argv) {
  std::string cell_path = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";
  std::string pose_text = "0.1,0.40,0";
  int trials = 256, seed = 1;
  double duration = 3.0;
  bool list_failures = false;
  rbsf::plan::CertificateSettings settings;
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
  app.add_flag("--list-failures", list_failures, "print each failed trial's draw");
  app.add_option("--friction-use", settings.feedback.forces.friction_use,
                 "the law's friction use of sticking contacts (default 0.8)")
      ->check(CLI::Range(0.05, 1.0));
  app.add_option("--margin-reward", settings.feedback.forces.margin_reward,
                 "the law's reward of the smallest margin (default 0.01)")
      ->check(CLI::Range(0.0, 100.0));
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
    if (list_failures) listFailures(part ? model : joints_only, plan, settings);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf_hold_bench", argc, argv, run);
}
