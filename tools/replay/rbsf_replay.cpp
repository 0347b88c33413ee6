// rbsf-replay: the certificate of a plan on a cell (rbsf/plan/certificate.h): the plan
// replayed in closed loop under the cell's sensing and uncertainty (--trials times, or in
// batches until the lower confidence bound of the success rate decides), judged by
// outcome. The cell may differ from the one the plan was made for (the parameters measured
// on the real cell); on the planning cell, with the certificate's seed and trial settings,
// it reproduces the plan file's certificate exactly. A cell with a `faults` section draws
// them in every trial (the executor's holds on: trial.h); --fault-table then also runs each
// kind of fault alone and prints how the trials ended (done, held, lost, off) per kind.
//
// Exit status: 0 certified; 4 not certified (verdict on stderr); 2 bad input (option,
// value, file, a plan for another number of fingers); 130 stopped by SIGINT, 143 by
// SIGTERM (nothing written); 1 internal error.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/trajectory_sample.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/fault_table.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/tools/certificate_options.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/interrupt.h"
#include "rbsf/tools/run_files.h"
#include "rbsf/tools/tool_main.h"

namespace rbsf::tools {
namespace {

constexpr int kExitNotCertified = 4;

int run(int argc, char** argv) {
  CLI::App app{
      "Certify a plan on a cell: replay it in closed loop under the cell's sensing and "
      "uncertainty (cell keys sensing and uncertainty) and judge each trial by outcome (the "
      "part ends at rest within 1 cm and 2 degrees of the goal, never dropped, inputs within "
      "their limits); certified when the one-sided 95 % Clopper-Pearson lower bound of the "
      "success rate is at least 0.95 (--confidence, --required-rate). The trials run in "
      "batches of 64 until that bound decides, at most 512 (--trial-batch, --max-trials), or "
      "exactly --trials N.",
      "rbsf-replay"};
  app.footer(
      "The law is the control law of the cell's sensing (part feedback, or joint feedback "
      "with part_pose: none), or the plan's inputs alone with --open-loop. With the plan's "
      "own cell and its certificate's seed and trial settings (--seed; --trials for a fixed "
      "count, else --trial-batch and --max-trials), the report equals the plan file's "
      "certificate.\n"
      "Exit status: 0 certified; 4 not certified (verdict on stderr); 2 bad input (option, "
      "value, file, a plan for another number of fingers), one message on stderr; 130 "
      "stopped by SIGINT, 143 by SIGTERM, nothing written; 1 internal error.");
  std::string cell, plan_path, seed_text = "1", out, csv;
  bool open_loop = false, fault_table = false;
  CertificateOptions certificate;
  app.add_option("--cell", cell, "cell YAML file (may differ from the planning cell)")->required();
  app.add_option("--plan", plan_path, "plan JSON file (plan-reorientation --out)")->required();
  certificate.addTo(app);
  app.add_option("--seed", seed_text, "seed of the draws, positive integer (default 1)");
  app.add_flag("--open-loop", open_loop, "the plan's inputs alone, no feedback");
  app.add_option("--out", out, "write the certificate as JSON");
  app.add_option("--csv", csv, "write the worst trial's trajectory as CSV (every step)");
  app.add_flag("--fault-table", fault_table,
               "with a cell that declares faults: also run each kind alone, with the same "
               "trials, and print how the trials ended per kind");
  parseCommandLine(app, argc, argv);

  plan::CertificateSettings settings;
  certificate.apply(settings);
  settings.seed = static_cast<std::uint64_t>(parseInteger(seed_text, "--seed", 1, 1LL << 53));
  settings.open_loop = open_loop;
  RunFiles files;  // no output replaces an input, another output or a special file
  files.addInput(cell, "--cell");
  files.addInput(plan_path, "--plan");
  files.addOutput(out, "--out");
  files.addOutput(csv, "--csv");

  const RbsfModel model(loadCell(cell));
  const plan::Plan plan = plan::readPlanJson(plan_path).plan;
  if (plan.q0.size() != model.configDim())
    throw InputError("--plan: the plan is for " + std::to_string(plan.q0.size() - 4) +
                     " fingers; the cell " + cell + " has " + std::to_string(model.numFingers()));
  if (fault_table && !model.cell().faults.any())
    throw InputError("--fault-table: the cell " + cell + " declares no faults (section faults)");
  const std::atomic<bool>& cancel = InterruptFlag::install();
  std::vector<plan::TrialOutcome> outcomes;
  const plan::Certificate c = plan::certify(model, plan, settings, &outcomes, &cancel);
  std::vector<plan::FaultRow> rows;
  if (fault_table) {
    for (const auto& [kind, alone] : plan::faultKinds(model.cell())) {
      std::vector<plan::TrialOutcome> kind_outcomes;
      plan::certify(RbsfModel(alone), plan, settings, &kind_outcomes, &cancel);
      rows.push_back(plan::faultRow(kind, kind_outcomes));
    }
    rows.push_back(plan::faultRow("all faults", outcomes));
  }
  if (InterruptFlag::raised()) {
    std::printf("interrupted: nothing written\n");
    return InterruptFlag::exitStatus();
  }
  std::printf("plan %s on cell %s\n", plan_path.c_str(), cell.c_str());
  std::fputs(plan::certificateReportText(c).c_str(), stdout);
  if (fault_table) std::fputs(plan::faultTableText(rows).c_str(), stdout);

  // Everything is formatted before any file is written.
  std::string csv_text;
  if (!csv.empty()) {
    std::vector<TrajectorySample> trace;
    plan::traceTrial(model, plan, settings, c.worst.index, trace);
    csv_text = trajectoryCsvText(trace, model.numFingers());
  }
  if (!out.empty()) {
    nlohmann::json j = {{"plan", plan_path}, {"cell", cell}};
    j["certificate"] = nlohmann::json::parse(plan::certificateJsonText(c));
    requireFinite(j, "the certificate");
    writeFileAtomically(out, j.dump(1) + "\n", "--out");
  }
  if (!csv.empty()) writeFileAtomically(csv, csv_text, "--csv");
  if (c.certified) return 0;
  std::fprintf(stderr, "rbsf-replay: %s\n", plan::verdictText(c).c_str());
  return kExitNotCertified;
}

}  // namespace
}  // namespace rbsf::tools

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf-replay", argc, argv, rbsf::tools::run);
}
