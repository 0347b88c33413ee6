#include "rbsf/plan/plan_file.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "certificate_json.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/dynamics/io/input_file.h"

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

template <class V>
V readVec(const json& j, const std::string& what) {
  if (!j.is_array()) throw InputError(what + " must be an array of numbers");
  // The fixed capacity is checked first: Eigen asserts it only in debug builds, so an
  // over-long array would overrun the inline storage in Release (found by fuzz_plan).
  constexpr auto capacity = static_cast<size_t>(V::MaxSizeAtCompileTime);
  if (j.size() > capacity)
    throw InputError(what + " has " + std::to_string(j.size()) + " entries; at most " +
                     std::to_string(capacity) + " are supported");
  V v(static_cast<int>(j.size()));
  for (size_t k = 0; k < j.size(); ++k) {
    if (!j[k].is_number() || !std::isfinite(j[k].get<double>()))
      throw InputError(what + " must be an array of finite numbers");
    v[static_cast<int>(k)] = j[k].get<double>();
  }
  return v;
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
  if (plan.cell.recorded)
    j["cell"] = {{"finger_r", plan.cell.finger_r},
                 {"part_mass", plan.cell.part_mass},
                 {"part_inertia", plan.cell.part_inertia},
                 {"gravity", plan.cell.gravity}};
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

PlanRecord readPlanJson(const std::string& path) {
  return parsePlanJson(readInputFile(path, "plan file"), path);
}

PlanRecord parsePlanJson(std::string_view text, const std::string& path) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(path + ": not JSON: " + e.what());
  }
  auto need = [&](const json& o, const char* key, const std::string& where) -> const json& {
    if (!o.is_object() || !o.contains(key))
      throw InputError(path + ": " + where + (where.empty() ? "" : ".") + key + " is missing");
    return o.at(key);
  };
  auto num = [&](const json& o, const char* key, const std::string& where) {
    const json& v = need(o, key, where);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      throw InputError(path + ": " + where + (where.empty() ? "" : ".") + key +
                       " must be a finite number");
    return v.get<double>();
  };
  // Integers are checked before conversion: a float or an out-of-range value cast to an
  // integer type is undefined behaviour (found by tests/fuzz/fuzz_plan.cpp).
  auto integer = [&](const json& o, const char* key, const std::string& where, double lo,
                     double hi) {
    const json& v = need(o, key, where);
    bool ok = false;
    if (v.is_number_unsigned()) {
      const auto u = static_cast<double>(v.get<std::uint64_t>());
      ok = u >= lo && u <= hi;
    } else if (v.is_number_integer()) {
      const auto i = static_cast<double>(v.get<std::int64_t>());
      ok = i >= lo && i <= hi;
    }
    if (!ok)
      throw InputError(path + ": " + where + (where.empty() ? "" : ".") + key +
                       " must be an integer in [" + std::to_string(static_cast<std::uint64_t>(lo)) +
                       ", " + std::to_string(static_cast<std::uint64_t>(hi)) + "]");
    return v.get<std::uint64_t>();
  };
  auto boolean = [&](const json& o, const char* key, const std::string& where) {
    const json& v = need(o, key, where);
    if (!v.is_boolean())
      throw InputError(path + ": " + where + (where.empty() ? "" : ".") + key +
                       " must be true or false");
    return v.get<bool>();
  };
  auto pose = [&](const char* key) {
    const json& p = need(j, key, "");
    return Pose{num(p, "x", key), num(p, "y", key), num(p, "phi", key)};
  };
  try {
    PlanRecord record;
    Plan& plan = record.plan;
    const std::string status = need(j, "status", "").get<std::string>();
    if (status != toString(PlanStatus::kExact) && status != toString(PlanStatus::kApproximate))
      throw InputError(path + ": status must be \"exact\" or \"approximate\"");
    plan.status =
        status == toString(PlanStatus::kExact) ? PlanStatus::kExact : PlanStatus::kApproximate;
    plan.planner = need(j, "planner", "").get<std::string>();
    plan.seed = static_cast<std::uint32_t>(integer(j, "seed", "", 0, 4294967295.0));
    if (j.contains("planning_time")) plan.planning_time = num(j, "planning_time", "");
    plan.propagations = integer(j, "propagations", "", 0, 1e18);
    plan.goal_distance = num(j, "goal_distance", "");
    SimulatorSettings& ss = plan.simulator;
    ss.time_step = num(j, "time_step", "");
    if (ss.time_step <= 0.0) throw InputError(path + ": time_step must be positive");
    if (j.contains("simulator")) {
      const json& sj = j.at("simulator");
      const std::string w = "simulator";
      if (sj.contains("activation_distance"))
        ss.activation_distance = num(sj, "activation_distance", w);
      if (sj.contains("contact_tolerance")) ss.contact_tolerance = num(sj, "contact_tolerance", w);
      if (sj.contains("slip_tolerance")) ss.slip_tolerance = num(sj, "slip_tolerance", w);
      if (sj.contains("regularization")) ss.regularization = num(sj, "regularization", w);
      if (sj.contains("curvature_terms")) ss.curvature_terms = boolean(sj, "curvature_terms", w);
      if (sj.contains("drift_correction")) ss.drift_correction = boolean(sj, "drift_correction", w);
      if (sj.contains("max_mode_iterations"))
        ss.max_mode_iterations = static_cast<int>(integer(sj, "max_mode_iterations", w, 0, 1000));
      try {
        Simulator::checkSettings(ss);
      } catch (const InputError& e) {
        throw InputError(path + ": " + e.what());
      }
    }
    plan.steps_per_control = static_cast<int>(integer(j, "steps_per_control", "", 1, 1e6));
    if (j.contains("feedback")) {
      const json& f = j.at("feedback");
      if (!f.is_string() || f.get<std::string>() != "joints")
        throw InputError(path + ": feedback must be \"joints\" when present");
      plan.joint_feedback = true;
    }
    plan.start = pose("start");
    plan.goal = pose("goal");
    plan.start_theta = num(j, "start_theta", "");
    plan.q0 = readVec<VecQ>(need(j, "q0", ""), path + ": q0");
    const int n = static_cast<int>(plan.q0.size());
    if (n < 5 || n > kMaxConfig) throw InputError(path + ": q0 has a wrong length");
    if (j.contains("cell")) {
      const json& c = j.at("cell");
      PlanCell& pc = plan.cell;
      pc.recorded = true;
      const json& r = need(c, "finger_r", "cell");
      if (!r.is_array() || static_cast<int>(r.size()) != n - 4)
        throw InputError(path + ": cell.finger_r needs one offset per finger");
      for (const json& x : r) {
        if (!x.is_number()) throw InputError(path + ": cell.finger_r must hold numbers");
        pc.finger_r.push_back(x.get<double>());
      }
      pc.part_mass = num(c, "part_mass", "cell");
      pc.part_inertia = num(c, "part_inertia", "cell");
      pc.gravity = num(c, "gravity", "cell");
    }
    for (const json& s : need(j, "segments", "")) {
      PlanSegment seg;
      seg.phase = parsePhase(need(s, "phase", "segments[]").get<std::string>());
      seg.duration = num(s, "duration", "segments[]");
      seg.steps = static_cast<int>(integer(s, "steps", "segments[]", 1, 1e9));
      seg.tau = readVec<VecU>(need(s, "tau", "segments[]"), path + ": segments[].tau");
      if (seg.tau.size() != n - 3 || seg.steps < 1)
        throw InputError(path + ": segments[] needs steps >= 1 and m + 1 taus");
      if (s.contains("tau_end")) {
        seg.tau_end = readVec<VecU>(s.at("tau_end"), path + ": segments[].tau_end");
        if (seg.tau_end.size() != n - 3)
          throw InputError(path + ": segments[].tau_end needs m + 1 values");
      }
      if (s.contains("contacts")) {
        if (!s.at("contacts").is_string())
          throw InputError(path + ": segments[].contacts must be a string");
        seg.contacts =
            parseRoles(s.at("contacts").get<std::string>(), n - 4, path + ": segments[].contacts");
      }
      plan.segments.push_back(std::move(seg));
    }
    for (const json& s : need(j, "samples", "")) {
      PlanSample p;
      p.t = num(s, "t", "samples[]");
      p.q = readVec<VecQ>(need(s, "q", "samples[]"), path + ": samples[].q");
      p.v = readVec<VecQ>(need(s, "v", "samples[]"), path + ": samples[].v");
      p.tau = readVec<VecU>(need(s, "tau", "samples[]"), path + ": samples[].tau");
      p.f_n = readVec<VecC>(need(s, "f_n", "samples[]"), path + ": samples[].f_n");
      // A step's phase may be "unsupported" (trajectory_sample.h); a segment's may not.
      const std::string phase = need(s, "phase", "samples[]").get<std::string>();
      p.phase = phase == toString(Phase::kUnsupported) ? Phase::kUnsupported : parsePhase(phase);
      if (p.q.size() != n || p.v.size() != n || p.tau.size() != n - 3 || p.f_n.size() != n - 4)
        throw InputError(path + ": samples[] entries have wrong lengths");
      plan.samples.push_back(std::move(p));
    }
    auto text = [&](const json& o, const char* key, const std::string& where) {
      const json& v = need(o, key, where);
      if (!v.is_string()) throw InputError(path + ": " + where + "." + key + " must be a string");
      return v.get<std::string>();
    };
    if (j.contains("optimization")) {
      const json& o = j.at("optimization");
      OptimizationSummary& s = record.optimization;
      s.ran = true;
      s.status =
          parseSolverStatus(text(o, "status", "optimization"), path + ": optimization.status");
      s.iterations = static_cast<int>(integer(o, "iterations", "optimization", 0, 1e9));
      if (o.contains("solve_time")) s.solve_time = num(o, "solve_time", "optimization");
      s.cost_before = num(o, "cost_before", "optimization");
      s.cost_after = num(o, "cost_after", "optimization");
      s.chosen = boolean(o, "chosen", "optimization");
      if (o.contains("refined_success_rate"))
        s.refined_success_rate = num(o, "refined_success_rate", "optimization");
      if (o.contains("message")) s.message = text(o, "message", "optimization");
    }
    if (j.contains("certificate"))
      record.certificate = readCertificateJson(j.at("certificate"), path + ": certificate");
    return record;
  } catch (const json::exception& e) {
    throw InputError(path + ": malformed plan: " + e.what());
  }
}

}  // namespace rbsf::plan
