#include "rbsf/dynamics/control/role_feasibility.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

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

bool RoleFeasibility::plantHoldsStuck(const ContactRoles& roles) const {
  const int m = model_.numFingers();
  const ModelData& d = qp_.contactData();
  const VecC& fn = qp_.normalForces();
  const VecC& ft = qp_.tangentialForces();
  // The touching contacts' force columns over every coordinate: a combination z with
  // W z = 0 is felt by no actuator and not by the part.
  int k = 0;
  std::array<int, kMaxFingers> finger{};
  for (int i = 0; i < m; ++i)
    if (roles[i] != ContactRole::kLifted && fn[i] > 0.0) finger[k++] = i;
  const int n = static_cast<int>(d.G1.rows());
  Eigen::MatrixXd W(n, 2 * k);
  for (int c = 0; c < k; ++c) {
    W.col(2 * c) = d.G1.col(finger[c]);
    W.col(2 * c + 1) = d.T.col(finger[c]);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(W, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  const double tol = 1e-9 * std::max(1.0, sv.size() > 0 ? sv[0] : 1.0);
  int rank = 0;
  for (int r = 0; r < sv.size(); ++r) rank += sv[r] > tol ? 1 : 0;
  const int free_dims = 2 * k - rank;
  if (free_dims == 0) return false;
  // More than one free internal force: the plant has room enough; count it as holding.
  if (free_dims > 1) return true;
  const Eigen::VectorXd z = svd.matrixV().col(2 * k - 1);
  // The interval of alpha for which lambda + alpha z keeps every touching contact pressed
  // and inside its cone at the plant's highest friction (a slider still stuck: at the pull's
  // breakaway x mu_s, what the pull is meant to exceed).
  const Cell& cell = model_.cell();
  const double mu_hi = cell.friction.mu_static * (1.0 + cell.uncertainty.static_friction);
  const double mu_pull = cell.friction.mu_static * qp_.settings().breakaway;
  double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
  bool possible = true;                  // no row that alpha cannot mend
  auto keep = [&](double a, double b) {  // a + alpha b >= 0
    if (std::abs(b) < 1e-12) {
      possible = possible && a >= 0.0;
    } else if (b > 0.0) {
      lo = std::max(lo, -a / b);
    } else {
      hi = std::min(hi, -a / b);
    }
  };
  for (int c = 0; c < k; ++c) {
    const int i = finger[c];
    const double mu = slipSign(roles[i]) != 0 ? mu_pull : mu_hi;
    const double zn = z[2 * c], zt = z[2 * c + 1];
    keep(fn[i], zn);
    keep(mu * fn[i] - ft[i], mu * zn - zt);
    keep(mu * fn[i] + ft[i], mu * zn + zt);
  }
  return possible && lo <= hi;
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
  else if (out.shortfall > settings_.row_tolerance || (breakaway && plantHoldsStuck(roles)))
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
