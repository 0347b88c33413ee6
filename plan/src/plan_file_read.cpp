// Reading a plan file (plan_file.h): every field checked, each error naming the file and the
// field; writing is in plan_file.cpp.
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "certificate_json.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/input_file.h"
#include "rbsf/plan/plan_file.h"

namespace rbsf::plan {

using nlohmann::json;

namespace {

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

/// The checked reading of a parsed plan file `root` read from `path`: each field's reader
/// throws InputError naming the file and the field ("where.key", or "key" at the top).
class PlanReader {
 public:
  PlanReader(const json& root, const std::string& path) : j_(root), path_(path) {}

  /// The record, its sections in the file's order.
  PlanRecord read() const;

 private:
  /// The value of `key` in object `o` (at `where`); throws when missing.
  const json& need(const json& o, const char* key, const std::string& where) const;
  /// A finite number.
  double num(const json& o, const char* key, const std::string& where) const;
  /// An integer in [lo, hi], checked before conversion: a float or an out-of-range value
  /// cast to an integer type is undefined behaviour (found by tests/fuzz/fuzz_plan.cpp).
  std::uint64_t integer(const json& o, const char* key, const std::string& where, double lo,
                        double hi) const;
  /// true or false.
  bool boolean(const json& o, const char* key, const std::string& where) const;
  /// A string.
  std::string text(const json& o, const char* key, const std::string& where) const;
  /// The top-level pose `key` {x, y, phi}.
  Pose pose(const char* key) const;

  /// status, planner, seed, planning_time, propagations and goal_distance.
  void readHeader(Plan& plan) const;
  /// time_step and the optional simulator settings, checked as the simulator checks them.
  void readSimulator(SimulatorSettings& ss) const;
  /// The optional cell `c` of a plan with `n` coordinates.
  void readCell(const json& c, int n, PlanCell& pc) const;
  /// Segment `s` of a plan with `n` coordinates.
  PlanSegment readSegment(const json& s, int n) const;
  /// Sample `s` of a plan with `n` coordinates.
  PlanSample readSample(const json& s, int n) const;
  /// The optimisation summary `o`.
  void readOptimization(const json& o, OptimizationSummary& s) const;

  const json& j_;
  const std::string& path_;
};

const json& PlanReader::need(const json& o, const char* key, const std::string& where) const {
  if (!o.is_object() || !o.contains(key))
    throw InputError(path_ + ": " + where + (where.empty() ? "" : ".") + key + " is missing");
  return o.at(key);
}

double PlanReader::num(const json& o, const char* key, const std::string& where) const {
  const json& v = need(o, key, where);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw InputError(path_ + ": " + where + (where.empty() ? "" : ".") + key +
                     " must be a finite number");
  return v.get<double>();
}

std::uint64_t PlanReader::integer(const json& o, const char* key, const std::string& where,
                                  double lo, double hi) const {
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
    throw InputError(path_ + ": " + where + (where.empty() ? "" : ".") + key +
                     " must be an integer in [" + std::to_string(static_cast<std::uint64_t>(lo)) +
                     ", " + std::to_string(static_cast<std::uint64_t>(hi)) + "]");
  return v.get<std::uint64_t>();
}

bool PlanReader::boolean(const json& o, const char* key, const std::string& where) const {
  const json& v = need(o, key, where);
  if (!v.is_boolean())
    throw InputError(path_ + ": " + where + (where.empty() ? "" : ".") + key +
                     " must be true or false");
  return v.get<bool>();
}

std::string PlanReader::text(const json& o, const char* key, const std::string& where) const {
  const json& v = need(o, key, where);
  if (!v.is_string()) throw InputError(path_ + ": " + where + "." + key + " must be a string");
  return v.get<std::string>();
}

Pose PlanReader::pose(const char* key) const {
  const json& p = need(j_, key, "");
  return Pose{num(p, "x", key), num(p, "y", key), num(p, "phi", key)};
}

PlanRecord PlanReader::read() const {
  PlanRecord record;
  Plan& plan = record.plan;
  readHeader(plan);
  readSimulator(plan.simulator);
  plan.steps_per_control = static_cast<int>(integer(j_, "steps_per_control", "", 1, 1e6));
  if (j_.contains("feedback")) {
    const json& f = j_.at("feedback");
    if (!f.is_string() || f.get<std::string>() != "joints")
      throw InputError(path_ + ": feedback must be \"joints\" when present");
    plan.joint_feedback = true;
  }
  plan.start = pose("start");
  plan.goal = pose("goal");
  plan.start_theta = num(j_, "start_theta", "");
  plan.q0 = readVec<VecQ>(need(j_, "q0", ""), path_ + ": q0");
  const int n = static_cast<int>(plan.q0.size());
  if (n < 5 || n > kMaxConfig) throw InputError(path_ + ": q0 has a wrong length");
  if (j_.contains("cell")) readCell(j_.at("cell"), n, plan.cell);
  for (const json& s : need(j_, "segments", "")) plan.segments.push_back(readSegment(s, n));
  for (const json& s : need(j_, "samples", "")) plan.samples.push_back(readSample(s, n));
  if (j_.contains("optimization")) readOptimization(j_.at("optimization"), record.optimization);
  if (j_.contains("certificate"))
    record.certificate = readCertificateJson(j_.at("certificate"), path_ + ": certificate");
  return record;
}

void PlanReader::readHeader(Plan& plan) const {
  const std::string status = need(j_, "status", "").get<std::string>();
  if (status != toString(PlanStatus::kExact) && status != toString(PlanStatus::kApproximate))
    throw InputError(path_ + ": status must be \"exact\" or \"approximate\"");
  plan.status =
      status == toString(PlanStatus::kExact) ? PlanStatus::kExact : PlanStatus::kApproximate;
  plan.planner = need(j_, "planner", "").get<std::string>();
  plan.seed = static_cast<std::uint32_t>(integer(j_, "seed", "", 0, 4294967295.0));
  if (j_.contains("planning_time")) plan.planning_time = num(j_, "planning_time", "");
  plan.propagations = integer(j_, "propagations", "", 0, 1e18);
  plan.goal_distance = num(j_, "goal_distance", "");
}

void PlanReader::readSimulator(SimulatorSettings& ss) const {
  ss.time_step = num(j_, "time_step", "");
  if (ss.time_step <= 0.0) throw InputError(path_ + ": time_step must be positive");
  if (!j_.contains("simulator")) return;
  const json& sj = j_.at("simulator");
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
    throw InputError(path_ + ": " + e.what());
  }
}

void PlanReader::readCell(const json& c, int n, PlanCell& pc) const {
  pc.recorded = true;
  const json& r = need(c, "finger_r", "cell");
  if (!r.is_array() || static_cast<int>(r.size()) != n - 4)
    throw InputError(path_ + ": cell.finger_r needs one offset per finger");
  for (const json& x : r) {
    if (!x.is_number()) throw InputError(path_ + ": cell.finger_r must hold numbers");
    pc.finger_r.push_back(x.get<double>());
  }
  pc.part_mass = num(c, "part_mass", "cell");
  pc.part_inertia = num(c, "part_inertia", "cell");
  pc.gravity = num(c, "gravity", "cell");
  if (c.contains("friction")) {
    const json& f = c.at("friction");
    if (!f.is_array() || f.size() != 2 || !f[0].is_number() || !f[1].is_number() ||
        !(f[0].get<double>() >= 0.0) || !(f[1].get<double>() >= 0.0))
      throw InputError(path_ + ": cell.friction must be [static, kinetic], two numbers >= 0");
    pc.friction_recorded = true;
    pc.mu_static = f[0].get<double>();
    pc.mu_kinetic = f[1].get<double>();
  }
}

PlanSegment PlanReader::readSegment(const json& s, int n) const {
  PlanSegment seg;
  seg.phase = parsePhase(need(s, "phase", "segments[]").get<std::string>());
  seg.duration = num(s, "duration", "segments[]");
  seg.steps = static_cast<int>(integer(s, "steps", "segments[]", 1, 1e9));
  seg.tau = readVec<VecU>(need(s, "tau", "segments[]"), path_ + ": segments[].tau");
  if (seg.tau.size() != n - 3 || seg.steps < 1)
    throw InputError(path_ + ": segments[] needs steps >= 1 and m + 1 taus");
  if (s.contains("tau_end")) {
    seg.tau_end = readVec<VecU>(s.at("tau_end"), path_ + ": segments[].tau_end");
    if (seg.tau_end.size() != n - 3)
      throw InputError(path_ + ": segments[].tau_end needs m + 1 values");
  }
  if (s.contains("contacts")) {
    if (!s.at("contacts").is_string())
      throw InputError(path_ + ": segments[].contacts must be a string");
    seg.contacts =
        parseRoles(s.at("contacts").get<std::string>(), n - 4, path_ + ": segments[].contacts");
  }
  return seg;
}

PlanSample PlanReader::readSample(const json& s, int n) const {
  PlanSample p;
  p.t = num(s, "t", "samples[]");
  p.q = readVec<VecQ>(need(s, "q", "samples[]"), path_ + ": samples[].q");
  p.v = readVec<VecQ>(need(s, "v", "samples[]"), path_ + ": samples[].v");
  p.tau = readVec<VecU>(need(s, "tau", "samples[]"), path_ + ": samples[].tau");
  p.f_n = readVec<VecC>(need(s, "f_n", "samples[]"), path_ + ": samples[].f_n");
  // A step's phase may be "unsupported" (trajectory_sample.h); a segment's may not.
  const std::string phase = need(s, "phase", "samples[]").get<std::string>();
  p.phase = phase == toString(Phase::kUnsupported) ? Phase::kUnsupported : parsePhase(phase);
  if (p.q.size() != n || p.v.size() != n || p.tau.size() != n - 3 || p.f_n.size() != n - 4)
    throw InputError(path_ + ": samples[] entries have wrong lengths");
  return p;
}

void PlanReader::readOptimization(const json& o, OptimizationSummary& s) const {
  s.ran = true;
  s.status = parseSolverStatus(text(o, "status", "optimization"), path_ + ": optimization.status");
  s.iterations = static_cast<int>(integer(o, "iterations", "optimization", 0, 1e9));
  if (o.contains("solve_time")) s.solve_time = num(o, "solve_time", "optimization");
  s.cost_before = num(o, "cost_before", "optimization");
  s.cost_after = num(o, "cost_after", "optimization");
  s.chosen = boolean(o, "chosen", "optimization");
  if (o.contains("refined_success_rate"))
    s.refined_success_rate = num(o, "refined_success_rate", "optimization");
  if (o.contains("message")) s.message = text(o, "message", "optimization");
}

}  // namespace

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
  try {
    return PlanReader(j, path).read();
  } catch (const json::exception& e) {
    throw InputError(path + ": malformed plan: " + e.what());
  }
}

}  // namespace rbsf::plan
