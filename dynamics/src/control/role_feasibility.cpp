#include "rbsf/dynamics/control/role_feasibility.h"

#include <algorithm>

namespace rbsf {

const char* toString(RoleRefusal r) {
  switch (r) {
    case RoleRefusal::kNone:
      return "none";
    case RoleRefusal::kRows:
      return "rows";
    case RoleRefusal::kBreakaway:
      return "breakaway";
    case RoleRefusal::kMargin:
      return "margin";
    case RoleRefusal::kMotion:
      return "motion";
  }
  return "rows";
}

RoleFeasibility::RoleFeasibility(const RbsfModel& model, const ContactForceSettings& forces,
                                 const RoleFeasibilitySettings& settings)
    : model_(model), settings_(settings), qp_(model, forces) {
  tick_.slip_floor = VecC::Zero(model.numFingers());
  zero_ = VecQ::Zero(model.configDim());
}

RoleVerdict RoleFeasibility::check(const VecQ& q, const ContactRoles& roles, bool sliders_loose,
                                   const VecU& feedforward, const VecQ& vdot) {
  const int m = model_.numFingers();
  RoleVerdict out;
  // The tick a law at rest at q would see: the planned contacts touching, sliders stuck
  // until loose, no slip floor (a slow slide needs none to be kept).
  tick_.roles = roles;
  for (int i = 0; i < m; ++i) {
    if (roles[i] == ContactRole::kUnplanned) return out;
    const bool lifted = roles[i] == ContactRole::kLifted;
    const bool slides = slipSign(roles[i]) != 0;
    tick_.estimated[i] = lifted                    ? ContactMode::kSeparated
                         : slides && sliders_loose ? ContactMode::kSlide
                                                   : ContactMode::kStick;
    tick_.loose[i] = slides && sliders_loose;
  }
  const VecQ& a = vdot.size() == q.size() ? vdot : zero_;
  bool breakaway = false;
  for (int i = 0; i < m; ++i) breakaway = breakaway || (slipSign(roles[i]) != 0 && !sliders_loose);
  qp_.solveForMotion(q, zero_, tick_, a, out.tau, feedforward);
  out.violation = qp_.violation();
  out.shortfall = qp_.shortfall();
  out.margin = qp_.margin();
  out.motion_error = qp_.motionError(out.tau, a);
  out.friction_use = qp_.frictionUse();
  out.fn = qp_.normalForces();
  out.ft = qp_.tangentialForces();
  const bool solved = qp_.status() == QpStatus::kOptimal;
  if (!solved || out.violation > settings_.row_tolerance)
    out.refusal = RoleRefusal::kRows;
  else if (out.shortfall > settings_.row_tolerance)
    out.refusal = RoleRefusal::kBreakaway;
  else if (settings_.robust && out.margin < 0.0)
    out.refusal = RoleRefusal::kMargin;
  else if (out.motion_error > settings_.motion_tolerance && !breakaway)
    out.refusal = RoleRefusal::kMotion;
  else
    out.refusal = RoleRefusal::kNone;
  out.feasible = out.refusal == RoleRefusal::kNone;
  return out;
}

}  // namespace rbsf
