/// \file
/// \brief plan-reorientation's output files (see plan_outputs.h).

#include "plan_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/planner/kinodynamic/goal.h"
#include "rbsf/tools/html_report.h"
#include "rbsf/tools/run_files.h"
#include "rbsf/tools/svg_animation.h"

namespace rbsf::tools {
namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[128];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

std::string poseText(const Pose& p) {
  return format("(%.3f m, %.3f m, %.1f deg)", p.x, p.y, p.phi * 180.0 / M_PI);
}

}  // namespace

std::string goalDistanceText(const VecQ& q, const Pose& goal, bool absolute_angle) {
  return format(
      "%.3g m and %.3g deg from the goal",
      std::hypot(q[layout::kX] - goal.x, q[layout::kY] - goal.y),
      std::abs(planner::goalAngleError(q[layout::kPhi], goal.phi, absolute_angle)) * 180 / M_PI);
}

PlanOutputs::PlanOutputs(PlanOutputOptions options) : o_(std::move(options)) {
  RunFiles files;  // no output replaces the cell, another output or a special file
  files.addInput(o_.cell_label, "--cell");
  files.addOutput(o_.json, "--out");
  files.addOutput(o_.csv, "--csv");
  files.addOutput(o_.svg, "--svg");
  files.addOutput(o_.report, "--report");
  if (!std::isfinite(o_.svg_still) || o_.svg_still < 0.0)
    throw InputError("--svg-still: must be a time >= 0 s");
}

bool PlanOutputs::any() const {
  return !o_.json.empty() || !o_.csv.empty() || !o_.svg.empty() || !o_.report.empty();
}

std::vector<TrajectorySample> PlanOutputs::frames(const RbsfModel& model, const plan::Plan& plan) {
  if (!plan.samples.empty()) return plan.samples;  // a plan's samples are trajectory samples
  const int m = model.numFingers();                // no motion: the part at rest at the start
  TrajectorySample f;
  f.q = plan.q0;
  f.v = VecQ::Zero(layout::configDim(m));
  f.tau = VecU::Zero(layout::controlDim(m));
  f.f_n = VecC::Zero(m);
  f.phase = Phase::kC;
  return {f};
}

void PlanOutputs::write(const RbsfModel& model, const plan::PlanRecord& record,
                        const std::vector<ReportSection>& sections) const {
  const plan::Plan& plan = record.plan;
  plan::PlanFileOptions file;
  file.wall_clock = !o_.reproducible;
  std::vector<std::pair<std::string, std::string>> texts;  // path, text: all formatted first
  if (!o_.json.empty()) texts.emplace_back(o_.json, plan::planJsonText(record, file));
  if (!o_.csv.empty()) texts.emplace_back(o_.csv, plan::planCsvText(plan));
  if (!o_.svg.empty() || !o_.report.empty()) {
    SvgAnimationOptions a;
    a.title = "plan-reorientation: " + o_.cell_label;
    a.subtitle = std::string(plan::toString(plan.status)) + " plan from " + poseText(plan.start) +
                 " to " + poseText(plan.goal) + " (dashed)";
    a.goal = plan.goal;
    a.still_time = o_.svg_still;
    if (!o_.svg.empty())
      texts.emplace_back(o_.svg, SvgAnimation(model, frames(model, plan), a).document());
    if (!o_.report.empty()) {
      std::vector<std::pair<std::string, std::string>> rows = {
          {"cell", o_.cell_label},
          {"status", std::string(plan::toString(plan.status))},
          {"start",
           poseText(plan.start) + format(", base %.1f deg", plan.start_theta * 180 / M_PI)},
          {"goal", poseText(plan.goal)},
          // A plan file does not say how its goal angle was read: modulo a turn here.
          {"end", goalDistanceText(frames(model, plan).back().q, plan.goal, false) +
                      " (angle modulo 360 deg)"},
          {"motion", format("%.3f s in %.0f segments", plan.duration(),
                            static_cast<double>(plan.segments.size()))},
          {"pivots", format("%.0f (planned phases ", static_cast<double>(plan.pivots())) +
                         plan.plannedPhases() + ")"},
          {"phase sequence", plan.phaseSequence()},
          {"search", plan.planner + format(", seed %.0f, %.0f propagations", plan.seed,
                                           static_cast<double>(plan.propagations))}};
      if (file.wall_clock) rows.emplace_back("planning time", format("%.3f s", plan.planning_time));
      ReportVerdict verdict;
      if (record.certificate.ran) {
        const plan::Certificate& c = record.certificate;
        verdict = {true, c.certified, plan::verdictText(c),
                   "Law: " + std::string(plan::toString(c.law)) + ". Worst " +
                       plan::worstTrialText(c) + "."};
        rows.emplace_back("certificate",
                          format("%.0f trials, seed %.0f", c.trials, static_cast<double>(c.seed)) +
                              "; " +
                              (c.sequential ? plan::stopText(c) : std::string("a fixed count")) +
                              format("; certified when the %g %% lower confidence bound is >= %g",
                                     100.0 * c.confidence, c.required_rate));
      } else {
        verdict = {true, false, "not certified: no closed-loop trials were run",
                   "Without the evidence of closed-loop trials this plan may not run on a cell."};
      }
      HtmlReport report(model, frames(model, plan), a, std::move(rows), std::move(verdict));
      for (const ReportSection& sec : sections) report.addSection(sec);
      texts.emplace_back(o_.report, report.render());
    }
  }
  const char* what[] = {"--out", "--csv", "--svg", "--report"};
  for (const auto& [path, text] : texts) {
    const char* w = path == o_.json  ? what[0]
                    : path == o_.csv ? what[1]
                    : path == o_.svg ? what[2]
                                     : what[3];
    writeFileAtomically(path, text, w);
  }
}

}  // namespace rbsf::tools
