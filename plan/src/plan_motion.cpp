#include "rbsf/plan/plan_motion.h"

#include <cmath>
#include <cstdio>

#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/plan.h"

namespace rbsf::plan {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string degrees(double rad) { return number(rad * 180.0 / M_PI); }

}  // namespace

PlanMotion measureMotion(const Plan& plan, const MotionLimits& limits) {
  PlanMotion m;
  m.limits = limits;
  if (plan.samples.empty()) return m;
  m.measured = true;
  for (const TrajectorySample& s : plan.samples) {
    const double speed = std::hypot(s.v[layout::kX], s.v[layout::kY]);
    const double turn = std::abs(s.v[layout::kPhi]);
    if (speed > m.peak_speed) m.peak_speed = speed, m.peak_speed_time = s.t;
    if (turn > m.peak_angular_speed) m.peak_angular_speed = turn, m.peak_angular_time = s.t;
  }
  const TrajectorySample& last = plan.samples.back();
  m.end_speed = std::hypot(last.v[layout::kX], last.v[layout::kY]);
  m.end_angular_speed = std::abs(last.v[layout::kPhi]);
  return m;
}

std::string motionViolationText(const PlanMotion& m) {
  if (!m.measured) return "the plan has no samples";
  std::string out;
  auto add = [&out](const std::string& s) { out += (out.empty() ? "" : "; ") + s; };
  if (m.peak_speed > m.limits.part_speed)
    add("moves the part at " + number(m.peak_speed) + " m/s at t = " + number(m.peak_speed_time) +
        " s (limit " + number(m.limits.part_speed) + " m/s)");
  if (m.peak_angular_speed > m.limits.angular_speed)
    add("turns the part at " + degrees(m.peak_angular_speed) + " deg/s at t = " +
        number(m.peak_angular_time) + " s (limit " + degrees(m.limits.angular_speed) + " deg/s)");
  if (m.end_speed > m.limits.rest_speed)
    add("ends moving at " + number(m.end_speed) + " m/s (rest: " + number(m.limits.rest_speed) +
        " m/s)");
  if (m.end_angular_speed > m.limits.rest_angular_speed)
    add("ends turning at " + degrees(m.end_angular_speed) +
        " deg/s (rest: " + degrees(m.limits.rest_angular_speed) + " deg/s)");
  return out;
}

std::string motionText(const PlanMotion& m) {
  if (!m.ok()) return "motion: OUTSIDE THE CELL'S LIMITS: " + motionViolationText(m);
  return "motion: peak " + number(m.peak_speed) + " m/s and " + degrees(m.peak_angular_speed) +
         " deg/s (limits " + number(m.limits.part_speed) + " m/s, " +
         degrees(m.limits.angular_speed) + " deg/s), ends at rest";
}

}  // namespace rbsf::plan
