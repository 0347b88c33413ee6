#include "certificate_json.h"

#include <cmath>
#include <cstdio>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/plan/confidence.h"

namespace rbsf::plan {

using nlohmann::json;

namespace {

json pair(double a, double b) { return json::array({a, b}); }

/// Strict reads with messages "<where>.<key> ...".
struct Reader {
  std::string where;

  const json& need(const json& o, const char* key) const {
    if (!o.is_object() || !o.contains(key)) throw InputError(where + "." + key + " is missing");
    return o.at(key);
  }
  double num(const json& o, const char* key) const {
    const json& v = need(o, key);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      throw InputError(where + "." + key + " must be a finite number");
    return v.get<double>();
  }
  bool boolean(const json& o, const char* key) const {
    const json& v = need(o, key);
    if (!v.is_boolean()) throw InputError(where + "." + key + " must be true or false");
    return v.get<bool>();
  }
  std::string text(const json& o, const char* key) const {
    const json& v = need(o, key);
    if (!v.is_string()) throw InputError(where + "." + key + " must be a string");
    return v.get<std::string>();
  }
  long integer(const json& o, const char* key, long lo, long hi) const {
    const json& v = need(o, key);
    if (!v.is_number_integer() || v.get<long>() < lo || v.get<long>() > hi)
      throw InputError(where + "." + key + " must be an integer in [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "]");
    return v.get<long>();
  }
  std::pair<double, double> pairOf(const json& o, const char* key) const {
    const json& v = need(o, key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
      throw InputError(where + "." + key + " must be a list of 2 numbers");
    return {v[0].get<double>(), v[1].get<double>()};
  }
  Reader sub(const char* key) const { return {where + "." + key}; }
};

/// The counts and their bound (law, trials, successes, success_rate, confidence,
/// lower_bound): a file whose bound does not follow from its counts is refused.
void readCounts(const Reader& rd, const json& j, Certificate& c) {
  c.law = parseTrialLaw(rd.text(j, "law"), rd.where + ".law");
  c.trials = static_cast<int>(rd.integer(j, "trials", 1, 100000));
  c.successes = static_cast<int>(rd.integer(j, "successes", 0, c.trials));
  c.success_rate = rd.num(j, "success_rate");
  c.confidence = rd.num(j, "confidence");
  if (!(c.confidence >= 0.5 && c.confidence < 1.0))
    throw InputError(rd.where + ".confidence must be in [0.5, 1)");
  // The bound follows from the counts: a file whose bound does not is refused, not trusted.
  c.lower_bound = rd.num(j, "lower_bound");
  const double bound = clopperPearsonLower(c.successes, c.trials, c.confidence);
  if (!(std::abs(c.lower_bound - bound) <= 1e-9)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  ".lower_bound must be the %g %% lower confidence bound of %d/%d trials (%.6g)",
                  100.0 * c.confidence, c.successes, c.trials, bound);
    throw InputError(rd.where + buf);
  }
}

/// `sequential`: false for a fixed count, else {batch, max_trials} with trials within.
void readSequential(const Reader& rd, const json& j, Certificate& c) {
  const json& sequential = rd.need(j, "sequential");
  if (sequential.is_object()) {
    const Reader qr = rd.sub("sequential");
    c.sequential = true;
    c.batch = static_cast<int>(qr.integer(sequential, "batch", 1, 100000));
    c.max_trials = static_cast<int>(qr.integer(sequential, "max_trials", c.batch, 100000));
    if (c.trials > c.max_trials)
      throw InputError(rd.where + ".trials must be at most sequential.max_trials");
  } else if (!(sequential.is_boolean() && !sequential.get<bool>())) {
    throw InputError(rd.where + ".sequential must be false or {batch, max_trials}");
  }
}

/// The success criteria `crit` (read by `cr`).
void readCriteria(const Reader& cr, const json& crit, Certificate& c) {
  c.position_tolerance = cr.num(crit, "position_tolerance");
  c.angle_tolerance = cr.num(crit, "angle_tolerance");
  c.rest_speed = cr.num(crit, "rest_speed");
  c.rest_angular_speed = cr.num(crit, "rest_angular_speed");
  c.settle_time = cr.num(crit, "settle_time");
}

/// The sensing `sensing` (read by `sr`): joint noise, and the part pose or "none".
void readSensing(const Reader& sr, const json& sensing, Sensing& out) {
  std::tie(out.joints.angle_noise, out.joints.stroke_noise) =
      sr.sub("joints").pairOf(sr.need(sensing, "joints"), "noise");
  const json& pose = sr.need(sensing, "part_pose");
  PartPoseSensing& pp = out.part_pose;
  pp.present = !(pose.is_string() && pose.get<std::string>() == "none");
  if (pp.present) {
    const Reader pr = sr.sub("part_pose");
    pp.rate = pr.num(pose, "rate");
    pp.latency = pr.num(pose, "latency");
    std::tie(pp.position_noise, pp.angle_noise) = pr.pairOf(pose, "noise");
  }
}

/// The uncertainty `u` (read by `ur`).
void readUncertainty(const Reader& ur, const json& u, Uncertainty& un) {
  un.mass = ur.num(u, "mass");
  un.inertia = ur.num(u, "inertia");
  un.com = ur.num(u, "com");
  un.static_friction = ur.num(u, "static_friction");
  std::tie(un.kinetic_friction_min, un.kinetic_friction_max) = ur.pairOf(u, "kinetic_friction");
  un.initial_position = ur.num(u, "initial_position");
  un.initial_angle = ur.num(u, "initial_angle");
  un.actuator_gain = ur.num(u, "actuator_gain");
}

/// The worst trial `w` (read by `wr`) of `trials`.
void readWorst(const Reader& wr, const json& w, int trials, TrialOutcome& o) {
  o.index = static_cast<int>(wr.integer(w, "trial", -1, trials - 1));
  o.success = wr.boolean(w, "success");
  o.failure = wr.text(w, "failure");
  o.position_error = wr.num(w, "position_error");
  o.angle_error = wr.num(w, "angle_error");
  o.speed = wr.num(w, "speed");
  o.angular_speed = wr.num(w, "angular_speed");
  o.dropped = wr.boolean(w, "dropped");
  if (o.dropped) o.dropped_time = wr.num(w, "dropped_time");
  o.saturated_time = wr.num(w, "saturated_time");
  o.min_f_n = wr.num(w, "min_f_n");
  o.max_deviation = wr.num(w, "max_deviation");
  o.phases = wr.text(w, "phases");
  if (w.contains("departure_time")) {
    o.departure_time = wr.num(w, "departure_time");
    o.departure_phase = wr.text(w, "departure_phase");
  }
}

/// The plan's motion `mj` (read by `mr`): its peaks, end speeds and limits.
void readMotion(const Reader& mr, const json& mj, PlanMotion& m) {
  m.measured = true;
  m.peak_speed = mr.num(mj, "peak_speed");
  m.peak_speed_time = mr.num(mj, "peak_speed_time");
  m.peak_angular_speed = mr.num(mj, "peak_angular_speed");
  m.peak_angular_time = mr.num(mj, "peak_angular_time");
  m.end_speed = mr.num(mj, "end_speed");
  m.end_angular_speed = mr.num(mj, "end_angular_speed");
  const Reader lr = mr.sub("limits");
  const json& lj = mr.need(mj, "limits");
  m.limits.part_speed = lr.num(lj, "part_speed");
  m.limits.angular_speed = lr.num(lj, "angular_speed");
  std::tie(m.limits.rest_speed, m.limits.rest_angular_speed) = lr.pairOf(lj, "rest");
}

/// The holding check `hj` (read by `hr`).
void readHolding(const Reader& hr, const json& hj, Certificate& c) {
  c.holding_required = true;
  c.holding.measured = hr.boolean(hj, "measured");
  c.holding.free_time = hr.num(hj, "free_time");
  c.holding.longest_free = hr.num(hj, "longest_free");
  c.holding.longest_free_start = hr.num(hj, "longest_free_start");
  c.holding.max_free_time = hr.num(hj, "max_free_time");
}

}  // namespace

json certificateJson(const Certificate& c) {
  const PartPoseSensing& pp = c.sensing.part_pose;
  json sensing = {
      {"joints", {{"noise", pair(c.sensing.joints.angle_noise, c.sensing.joints.stroke_noise)}}}};
  if (pp.present)
    sensing["part_pose"] = {{"rate", pp.rate},
                            {"latency", pp.latency},
                            {"noise", pair(pp.position_noise, pp.angle_noise)}};
  else
    sensing["part_pose"] = "none";
  const Uncertainty& u = c.uncertainty;
  const TrialOutcome& w = c.worst;
  json worst = {{"trial", w.index},
                {"success", w.success},
                {"failure", w.failure},
                {"position_error", w.position_error},
                {"angle_error", w.angle_error},
                {"speed", w.speed},
                {"angular_speed", w.angular_speed},
                {"dropped", w.dropped},
                {"saturated_time", w.saturated_time},
                {"min_f_n", w.min_f_n},
                {"max_deviation", w.max_deviation},
                {"phases", w.phases}};
  if (w.dropped) worst["dropped_time"] = w.dropped_time;
  if (w.departure_time >= 0.0) {
    worst["departure_time"] = w.departure_time;
    worst["departure_phase"] = w.departure_phase;
  }
  json out = {{"law", toString(c.law)},
              {"trials", c.trials},
              {"successes", c.successes},
              {"success_rate", c.success_rate},
              {"lower_bound", c.lower_bound},
              {"confidence", c.confidence},
              {"required_rate", c.required_rate},
              {"certified", c.certified},
              {"seed", c.seed},
              {"criteria",
               {{"position_tolerance", c.position_tolerance},
                {"angle_tolerance", c.angle_tolerance},
                {"rest_speed", c.rest_speed},
                {"rest_angular_speed", c.rest_angular_speed},
                {"settle_time", c.settle_time}}},
              {"sensing", sensing},
              {"uncertainty",
               {{"mass", u.mass},
                {"inertia", u.inertia},
                {"com", u.com},
                {"static_friction", u.static_friction},
                {"kinetic_friction", pair(u.kinetic_friction_min, u.kinetic_friction_max)},
                {"initial_position", u.initial_position},
                {"initial_angle", u.initial_angle},
                {"actuator_gain", u.actuator_gain}}},
              {"worst", worst}};
  if (c.sequential)
    out["sequential"] = {{"batch", c.batch}, {"max_trials", c.max_trials}};
  else
    out["sequential"] = false;
  const PlanMotion& m = c.motion;
  if (m.measured)
    out["motion"] = {{"peak_speed", m.peak_speed},
                     {"peak_speed_time", m.peak_speed_time},
                     {"peak_angular_speed", m.peak_angular_speed},
                     {"peak_angular_time", m.peak_angular_time},
                     {"end_speed", m.end_speed},
                     {"end_angular_speed", m.end_angular_speed},
                     {"limits",
                      {{"part_speed", m.limits.part_speed},
                       {"angular_speed", m.limits.angular_speed},
                       {"rest", pair(m.limits.rest_speed, m.limits.rest_angular_speed)}}}};
  if (c.holding_required)
    out["holding"] = {{"measured", c.holding.measured},
                      {"free_time", c.holding.free_time},
                      {"longest_free", c.holding.longest_free},
                      {"longest_free_start", c.holding.longest_free_start},
                      {"max_free_time", c.holding.max_free_time}};
  return out;
}

Certificate readCertificateJson(const json& j, const std::string& where) {
  const Reader rd{where};
  Certificate c;
  c.ran = true;
  readCounts(rd, j, c);
  c.required_rate = rd.num(j, "required_rate");
  c.certified = rd.boolean(j, "certified");
  readSequential(rd, j, c);
  const json& seed = rd.need(j, "seed");
  if (!seed.is_number_unsigned()) throw InputError(where + ".seed must be an unsigned integer");
  c.seed = seed.get<std::uint64_t>();
  readCriteria(rd.sub("criteria"), rd.need(j, "criteria"), c);
  readSensing(rd.sub("sensing"), rd.need(j, "sensing"), c.sensing);
  readUncertainty(rd.sub("uncertainty"), rd.need(j, "uncertainty"), c.uncertainty);
  readWorst(rd.sub("worst"), rd.need(j, "worst"), c.trials, c.worst);
  if (j.contains("motion")) readMotion(rd.sub("motion"), j.at("motion"), c.motion);
  if (j.contains("holding")) readHolding(rd.sub("holding"), j.at("holding"), c);
  return c;
}

std::string certificateJsonText(const Certificate& certificate) {
  return certificateJson(certificate).dump(1) + "\n";
}

}  // namespace rbsf::plan
