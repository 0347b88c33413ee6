// Writing a plan file (plan_file.h); reading is in plan_file_read.cpp.
#include "rbsf/plan/plan_file.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "certificate_json.h"
#include "rbsf/dynamics/io/atomic_file.h"

namespace rbsf::plan {

using nlohmann::json;

namespace {

json vec(const auto& v) {
  json a = json::array();
  for (int k = 0; k < v.size(); ++k) a.push_back(v[k]);
  return a;
}

json poseJson(const Pose& p) { return {{"x", p.x}, {"y", p.y}, {"phi", p.phi}}; }

void requireFiniteJson(const json& j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    throw std::runtime_error("plan holds a NaN or infinite value; not written");
  if (j.is_structured())
    for (const json& e : j) requireFiniteJson(e);
}

}  // namespace

std::string planJsonText(const PlanRecord& record, const PlanFileOptions& options) {
  const Plan& plan = record.plan;
  json segs = json::array();
  for (const PlanSegment& s : plan.segments) {
    json seg = {{"phase", std::string(toString(s.phase))},
                {"duration", s.duration},
                {"steps", s.steps},
                {"tau", vec(s.tau)}};
    if (s.tau_end.size() > 0) seg["tau_end"] = vec(s.tau_end);
    if (planned(s.contacts))
      seg["contacts"] = rolesText(s.contacts, static_cast<int>(s.tau.size()) - 1);
    segs.push_back(std::move(seg));
  }
  json samples = json::array();
  for (const PlanSample& s : plan.samples)
    samples.push_back({{"t", s.t},
                       {"q", vec(s.q)},
                       {"v", vec(s.v)},
                       {"tau", vec(s.tau)},
                       {"f_n", vec(s.f_n)},
                       {"phase", std::string(toString(s.phase))}});
  json j = json::object();
  j["status"] = toString(plan.status);
  j["planner"] = plan.planner;
  j["seed"] = plan.seed;
  if (options.wall_clock) j["planning_time"] = plan.planning_time;
  j["propagations"] = plan.propagations;
  j["goal_distance"] = plan.goal_distance;
  j["time_step"] = plan.simulator.time_step;
  const SimulatorSettings& ss = plan.simulator;
  j["simulator"] = {
      {"activation_distance", ss.activation_distance}, {"contact_tolerance", ss.contact_tolerance},
      {"slip_tolerance", ss.slip_tolerance},           {"regularization", ss.regularization},
      {"curvature_terms", ss.curvature_terms},         {"drift_correction", ss.drift_correction},
      {"max_mode_iterations", ss.max_mode_iterations}};
  j["steps_per_control"] = plan.steps_per_control;
  if (plan.joint_feedback) j["feedback"] = "joints";
  j["start"] = poseJson(plan.start);
  j["start_theta"] = plan.start_theta;
  j["goal"] = poseJson(plan.goal);
  j["q0"] = vec(plan.q0);
  if (plan.cell.recorded) {
    j["cell"] = {{"finger_r", plan.cell.finger_r},
                 {"part_mass", plan.cell.part_mass},
                 {"part_inertia", plan.cell.part_inertia},
                 {"gravity", plan.cell.gravity}};
    if (plan.cell.friction_recorded)
      j["cell"]["friction"] = {plan.cell.mu_static, plan.cell.mu_kinetic};
  }
  j["phase_sequence"] = plan.phaseSequence();
  j["segments"] = segs;
  j["samples"] = samples;
  if (record.optimization.ran) {
    const OptimizationSummary& o = record.optimization;
    j["optimization"] = {{"status", toString(o.status)},
                         {"iterations", o.iterations},
                         {"cost_before", o.cost_before},
                         {"cost_after", o.cost_after}};
    if (options.wall_clock) j["optimization"]["solve_time"] = o.solve_time;
    j["optimization"]["chosen"] = o.chosen;
    if (o.refined_success_rate >= 0.0)
      j["optimization"]["refined_success_rate"] = o.refined_success_rate;
    if (!o.message.empty()) j["optimization"]["message"] = o.message;
  }
  if (record.certificate.ran) j["certificate"] = certificateJson(record.certificate);
  requireFiniteJson(j);
  return j.dump(1) + "\n";
}

void writePlanJson(const PlanRecord& record, const std::string& path,
                   const PlanFileOptions& options) {
  writeFileAtomically(path, planJsonText(record, options), "plan file");
}

}  // namespace rbsf::plan
