#include "rbsf/planner/support/support_geometry.h"

#include <cmath>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {
namespace {

Mat2 rotation(double a) {
  Mat2 R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R;
}

}  // namespace

ContactRoles supportRoles(const ContactSet& set, const VecC& slip, int m) {
  ContactRoles roles{};
  for (int i = 0; i < m; ++i) {
    if (!set.touches(i))
      roles[i] = ContactRole::kLifted;
    else if (set.sticks(i))
      roles[i] = ContactRole::kStick;
    else if (slip.size() > i && std::abs(slip[i]) > kSlipStep)
      roles[i] = slip[i] > 0.0 ? ContactRole::kSlidePositive : ContactRole::kSlideNegative;
    else
      roles[i] = ContactRole::kFree;
  }
  return roles;
}

Pose JigPose::world() const {
  const Vec2 p = rotation(theta) * Vec2(X, Y);
  return Pose{p.x(), p.y(), psi + theta};
}

JigPose JigPose::fromWorld(const Pose& p, double theta) {
  const Vec2 b = rotation(-theta) * Vec2(p.x, p.y);
  return JigPose{b.x(), b.y(), p.phi - theta, theta};
}

double poseDistance(const JigPose& a, const JigPose& b, double length_scale) {
  const double dx = (a.X - b.X) / length_scale, dy = (a.Y - b.Y) / length_scale;
  const double dp = a.psi - b.psi, dt = a.theta - b.theta;
  return std::sqrt(dx * dx + dy * dy + dp * dp + dt * dt);
}

SupportGeometry::SupportGeometry(const RbsfModel& model, SupportSettings settings)
    : model_(model),
      settings_(settings),
      balancer_(model, settings.balance),
      law_(model, settings.law, settings.roles),
      data_(model.numFingers()) {}

bool SupportGeometry::entry(const JigPose& pose, int i, double& stroke, double& xi,
                            double min_cosine) const {
  // The finger's line, base frame: (r_i, -L) + s (0, 1); in the part frame.
  const Shape& shape = model_.shape();
  const double L = 2.0 * shape.boundingRadius() + std::abs(pose.Y) + 1.0;
  const Mat2 Rt = rotation(-pose.psi);
  const Vec2 origin = Rt * (Vec2(model_.cell().fingers[i].r, -L) - Vec2(pose.X, pose.Y));
  const Vec2 dir = Rt * Vec2(0.0, 1.0);
  double s = 0.0;
  if (!shape.entryAlongLine(origin, dir, s, xi)) return false;
  // The underside only: the inward normal must push along the finger's axis.
  if (shape.boundary(xi).normal.dot(dir) < min_cosine) return false;
  stroke = s - L;
  return true;
}

std::optional<VecQ> SupportGeometry::configuration(const JigPose& pose, const ContactSet& set,
                                                   bool check_limits, SupportRule* why) const {
  const Cell& cell = model_.cell();
  auto fail = [why](SupportRule rule) {
    if (why != nullptr) *why = rule;
    return std::nullopt;
  };
  if (check_limits && (pose.theta < cell.base.theta_min + settings_.theta_margin ||
                       pose.theta > cell.base.theta_max - settings_.theta_margin))
    return fail(SupportRule::kBaseLimit);
  const int m = model_.numFingers();
  const Pose w = pose.world();
  VecQ q(model_.configDim());
  q[layout::kX] = w.x;
  q[layout::kY] = w.y;
  q[layout::kPhi] = w.phi;
  q[layout::kTheta] = pose.theta;
  for (int i = 0; i < m; ++i) {
    const FingerParams& f = cell.fingers[i];
    if (set.touches(i)) {
      double stroke = 0.0, xi = 0.0;
      const double min_cosine =
          set.sticks(i) ? settings_.min_sticking_cosine : settings_.min_normal_cosine;
      if (!entry(pose, i, stroke, xi, min_cosine)) return fail(SupportRule::kReach);
      if (check_limits && (stroke < f.stroke_min + settings_.stroke_margin ||
                           stroke > f.stroke_max - settings_.stroke_margin))
        return fail(SupportRule::kStroke);
      q[layout::stroke(i)] = stroke;
    } else {
      q[layout::stroke(i)] = f.stroke_min;
      // A retracted tip must stay clear of the part.
      const Vec2 tip = rotation(-pose.psi) * (Vec2(f.r, f.stroke_min) - Vec2(pose.X, pose.Y));
      // Newton from the tip's polar angle: exact below the part (closestNear certifies it
      // or falls back to the global scan), and several times cheaper than the scan.
      if (check_limits &&
          model_.shape().closestNear(tip, std::atan2(tip.y(), tip.x())).signed_distance <
              settings_.clearance)
        return fail(SupportRule::kClearance);
    }
  }
  return q;
}

Support SupportGeometry::check(const JigPose& pose, const ContactSet& set, const VecC& slip) {
  Support out;
  const std::optional<VecQ> q = configuration(pose, set, true, &out.refusal);
  if (!q) return out;
  return balanceAt(*q, set, slip);
}

Support SupportGeometry::balanceAt(const VecQ& q, const ContactSet& set, const VecC& slip) {
  Support out;
  out.q = q;
  out.balance = balancer_.statics(out.q, set, data_, slip);
  out.margin = out.balance.margin;
  out.valid = out.balance.balanced && (!settings_.require_determined || out.balance.determined);
  out.refusal = out.balance.balanced ? SupportRule::kUndetermined : SupportRule::kBalance;
  out.law.feasible = true;
  if (out.valid && settings_.law_check) {
    out.law = lawCheck(q, set, slip, true, out.balance.tau);
    out.valid = out.law.feasible;
    out.refusal = SupportRule::kLaw;
  }
  return out;
}

bool SupportGeometry::breaksAway(const VecQ& q, const ContactSet& set, const VecC& slip) {
  if (set.sticking == set.touching) return true;
  const ContactBalance b = balancer_.breakaway(q, set, data_, slip);
  if (!b.balanced) return false;
  return !settings_.law_check || lawCheck(q, set, slip, false, b.tau).feasible;
}

bool SupportGeometry::handsOver(const JigPose& pose, const ContactSet& from, const VecQ& q_from,
                                const ContactSet& to, const VecQ& q_to) {
  if (!settings_.law_check) return true;
  const ContactSet both{from.touching | to.touching, from.sticking & to.sticking};
  const std::optional<VecQ> q = configuration(pose, both, false);
  if (!q) return false;
  const VecU tau =
      0.5 * (balancer_.statics(q_from, from, data_).tau + balancer_.statics(q_to, to, data_).tau);
  return lawCheck(*q, both, VecC(), true, tau).feasible;
}

RoleVerdict SupportGeometry::lawCheck(const VecQ& q, const ContactSet& set, const VecC& slip,
                                      bool loose, const VecU& tau) {
  return law_.check(q, supportRoles(set, slip, model_.numFingers()), loose, tau);
}

VecC SupportGeometry::slipDirections(const VecQ& q0, const VecQ& q1) {
  model_.updateContacts(q0, data_);
  const VecQ dq = q1 - q0;
  VecC s(model_.numFingers());
  for (int i = 0; i < s.size(); ++i) s[i] = data_.T.col(i).dot(dq);
  return s;
}

JigPose SupportGeometry::pivotPose(const PivotAnchor& anchor, double psi, double theta) const {
  const Vec2 tip(model_.cell().fingers[anchor.finger].r, anchor.stroke);
  const Vec2 p = tip - rotation(psi) * model_.shape().point(anchor.xi);
  return JigPose{p.x(), p.y(), psi, theta};
}

bool SupportGeometry::pivotOnto(const PivotAnchor& anchor, const Pose& goal, double psi_near,
                                double& psi, double& theta, double& stroke) const {
  const Vec2 w = Vec2(goal.x, goal.y) + rotation(goal.phi) * model_.shape().point(anchor.xi);
  const Cell& cell = model_.cell();
  const FingerParams& f = cell.fingers[anchor.finger];
  const double l2 = w.squaredNorm() - f.r * f.r;
  if (l2 <= 0.0) return false;
  stroke = std::sqrt(l2);
  theta = std::atan2(w.y(), w.x()) - std::atan2(stroke, f.r);
  psi = goal.phi - theta;
  psi += 2.0 * M_PI * std::round((psi_near - psi) / (2.0 * M_PI));
  return theta >= cell.base.theta_min + settings_.theta_margin &&
         theta <= cell.base.theta_max - settings_.theta_margin &&
         stroke >= f.stroke_min + settings_.stroke_margin &&
         stroke <= f.stroke_max - settings_.stroke_margin;
}

ContactSet SupportGeometry::placedSet(const JigPose& pose) const {
  ContactSet set;
  for (int i = 0; i < model_.numFingers(); ++i) {
    const FingerParams& f = model_.cell().fingers[i];
    double stroke = 0.0, xi = 0.0;
    if (entry(pose, i, stroke, xi) && stroke >= f.stroke_min + settings_.stroke_margin &&
        stroke <= f.stroke_max - settings_.stroke_margin)
      set.touching |= 1u << i;
  }
  return set;
}

}  // namespace rbsf::planner
