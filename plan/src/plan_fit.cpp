#include "rbsf/plan/plan_fit.h"

#include <cmath>
#include <sstream>

#include "rbsf/dynamics/core/model_data.h"

namespace rbsf::plan {

namespace {

bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); }

std::string differs(const std::string& what, double plan, double cell, const char* unit,
                    const char* made = "the plan was made for another cell: ") {
  std::ostringstream s;
  s << made << what << " is " << plan << (*unit != 0 ? " " : "") << unit << " in the plan, " << cell
    << (*unit != 0 ? " " : "") << unit << " in this cell";
  return s.str();
}

}  // namespace

std::string planCellMismatch(const RbsfModel& model, const Plan& plan) {
  const Cell& cell = model.cell();
  const int m = model.numFingers(), n = model.configDim(), nu = model.controlDim();
  const int plan_m = static_cast<int>(plan.q0.size()) - 4;
  if (plan.q0.size() != n)
    return "the plan was made for another cell: " + std::to_string(plan_m) +
           " fingers in the plan, " + std::to_string(m) + " in this cell";
  if (plan.segments.empty() || plan.samples.empty()) return "the plan has no segments or samples";
  for (const PlanSegment& s : plan.segments)
    if (s.tau.size() != nu || (s.tau_end.size() != 0 && s.tau_end.size() != nu))
      return "the plan's segments have inputs sized for another cell";
  for (const PlanSample& s : plan.samples)
    if (s.q.size() != n || s.v.size() != n || s.tau.size() != nu || s.f_n.size() != m)
      return "the plan's samples are sized for another cell";
  if (plan.cell.recorded) {
    const PlanCell& c = plan.cell;
    if (static_cast<int>(c.finger_r.size()) != m)
      return "the plan's cell record has " + std::to_string(c.finger_r.size()) + " fingers";
    for (int i = 0; i < m; ++i)
      if (!same(c.finger_r[i], cell.fingers[i].r))
        return differs("finger " + std::to_string(i + 1) + "'s offset r", c.finger_r[i],
                       cell.fingers[i].r, "m");
    if (!same(c.part_mass, cell.object.mass))
      return differs("the part's mass", c.part_mass, cell.object.mass, "kg");
    if (!same(c.part_inertia, cell.object.inertia))
      return differs("the part's inertia", c.part_inertia, cell.object.inertia, "kg m^2");
    if (!same(c.gravity, cell.gravity)) return differs("gravity", c.gravity, cell.gravity, "m/s^2");
  }
  // The part rests on the fingers the plan starts with (its first sample's forces): their
  // tips lie on this cell's part at q0, or the part's shape or the fingers differ.
  ModelData data(m);
  model.updateContacts(plan.q0, data);
  for (int i = 0; i < m; ++i)
    if (plan.samples.front().f_n[i] > 0.0 && !(std::abs(data.contacts[i].gap) <= 1e-5)) {
      std::ostringstream s;
      s << "the plan was made for another cell: at the plan's start finger " << i + 1
        << "'s tip is " << data.contacts[i].gap
        << " m from this cell's part, where the plan has it touch (the part's shape or the "
           "fingers differ)";
      return s.str();
    }
  return "";
}

std::string certificateCellMismatch(const RbsfModel& model, const PlanRecord& record) {
  const Cell& cell = model.cell();
  const PlanCell& pc = record.plan.cell;
  if (pc.recorded && pc.friction_recorded) {
    const char* made = "the plan was planned and certified for other friction: ";
    if (!same(pc.mu_static, cell.friction.mu_static))
      return differs("static friction mu_s", pc.mu_static, cell.friction.mu_static, "", made);
    if (!same(pc.mu_kinetic, cell.friction.mu_kinetic))
      return differs("kinetic friction mu_k", pc.mu_kinetic, cell.friction.mu_kinetic, "", made);
  }
  const Certificate& c = record.certificate;
  if (!c.ran) return "";
  const char* drawn = "the plan's certificate was drawn for another cell: ";
  const Uncertainty& a = c.uncertainty;
  const Uncertainty& b = cell.uncertainty;
  const struct {
    const char* key;
    double plan, cell;
    const char* unit;
  } fields[] = {
      {"uncertainty.mass", a.mass, b.mass, ""},
      {"uncertainty.inertia", a.inertia, b.inertia, ""},
      {"uncertainty.com", a.com, b.com, "m"},
      {"uncertainty.static_friction", a.static_friction, b.static_friction, ""},
      {"uncertainty.kinetic_friction (min)", a.kinetic_friction_min, b.kinetic_friction_min, ""},
      {"uncertainty.kinetic_friction (max)", a.kinetic_friction_max, b.kinetic_friction_max, ""},
      {"uncertainty.initial_position", a.initial_position, b.initial_position, "m"},
      {"uncertainty.initial_angle", a.initial_angle, b.initial_angle, "rad"},
      {"uncertainty.actuator_gain", a.actuator_gain, b.actuator_gain, ""},
  };
  for (const auto& f : fields)
    if (!same(f.plan, f.cell)) return differs(f.key, f.plan, f.cell, f.unit, drawn);
  const Sensing& law = cell.sensing;
  const Sensing& cs = c.sensing;
  if (!same(cs.joints.angle_noise, law.joints.angle_noise))
    return differs("sensing.joints noise (angle)", cs.joints.angle_noise, law.joints.angle_noise,
                   "rad", drawn);
  if (!same(cs.joints.stroke_noise, law.joints.stroke_noise))
    return differs("sensing.joints noise (stroke)", cs.joints.stroke_noise, law.joints.stroke_noise,
                   "m", drawn);
  if (cs.part_pose.present != law.part_pose.present)
    return std::string(drawn) + "its cell " + (cs.part_pose.present ? "saw" : "did not see") +
           " the part's pose, this cell " + (law.part_pose.present ? "sees" : "does not see") +
           " it";
  if (law.part_pose.present) {
    const PartPoseSensing &p = cs.part_pose, &q = law.part_pose;
    if (!same(p.rate, q.rate))
      return differs("sensing.part_pose rate", p.rate, q.rate, "Hz", drawn);
    if (!same(p.latency, q.latency))
      return differs("sensing.part_pose latency", p.latency, q.latency, "s", drawn);
    if (!same(p.position_noise, q.position_noise))
      return differs("sensing.part_pose noise (position)", p.position_noise, q.position_noise, "m",
                     drawn);
    if (!same(p.angle_noise, q.angle_noise))
      return differs("sensing.part_pose noise (angle)", p.angle_noise, q.angle_noise, "rad", drawn);
  }
  return "";
}

}  // namespace rbsf::plan
