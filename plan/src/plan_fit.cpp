#include "rbsf/plan/plan_fit.h"

#include <cmath>
#include <sstream>

#include "rbsf/dynamics/core/model_data.h"

namespace rbsf::plan {

namespace {

bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); }

std::string differs(const std::string& what, double plan, double cell, const char* unit) {
  std::ostringstream s;
  s << "the plan was made for another cell: " << what << " is " << plan << " " << unit
    << " in the plan, " << cell << " " << unit << " in this cell";
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

}  // namespace rbsf::plan
