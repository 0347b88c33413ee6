#include "rbsf/dynamics/phase_control.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/QR>

#include "rbsf/dynamics/small_solvers.h"
#include "rbsf/dynamics/stick_dynamics.h"

namespace rbsf {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Pulls sampled extremes inside the range: an LP vertex sits on the boundary, where the
// least-norm solve's feasibility test would otherwise be decided by rounding.
constexpr double kInterior = 1.0 - 1e-6;
// The solvers accept a constraint violated by about 1e-9 of the forces' size; solving
// against limits this much tighter keeps the returned tau and F_n inside the true ones.
constexpr double kLimitShrink = 1e-6;

// min and max of c^T x + offset over the LP's feasible set.
AccelRange lpRange(const VectorXd& c, double offset, const MatrixXd& A_eq, const VectorXd& b_eq,
                   const MatrixXd& G, const VectorXd& h, const VectorXd& lower,
                   const VectorXd& upper) {
  AccelRange out;
  VectorXd x;
  double value = 0.0;
  try {
    SolveStatus s = solveLp(c, A_eq, b_eq, G, h, lower, upper, x, &value);
    if (s == SolveStatus::kInfeasible) return out;
    out.min = s == SolveStatus::kUnbounded ? -kInf : value + offset;
    s = solveLp(-c, A_eq, b_eq, G, h, lower, upper, x, &value);
    if (s == SolveStatus::kInfeasible) return AccelRange{};
    out.max = s == SolveStatus::kUnbounded ? kInf : -value + offset;
  } catch (const std::runtime_error&) {
    // The simplex guard only trips through rounding trouble; a sampler just draws again.
    return AccelRange{};
  }
  out.feasible = true;
  return out;
}

double fromFraction(const AccelRange& r, double f) {
  f = std::clamp(std::isnan(f) ? 0.0 : f, -1.0, 1.0) * kInterior;
  if (r.min <= 0.0 && r.max >= 0.0) return f >= 0.0 ? f * r.max : -f * r.min;
  return 0.5 * (r.min + r.max) + f * 0.5 * (r.max - r.min);
}

bool finite(const AccelRange& r) { return std::isfinite(r.min) && std::isfinite(r.max); }

}  // namespace

PhaseControl::PhaseControl(const RbsfModel& model, const PhaseControlOptions& options)
    : model_(&model), options_(options), m_(model.numFingers()) {
  const Cell& cell = model.cell();
  limit_.resize(model.controlDim());
  limit_[layout::kTauTheta] = cell.base.torque_limit;
  for (int i = 0; i < m_; ++i) limit_[layout::fingerForce(i)] = cell.fingers[i].force_limit;
  solve_limit_ = (1.0 - kLimitShrink) * limit_;
  f_min_ = options.min_normal_fraction * cell.object.mass * cell.gravity +
           kLimitShrink * limit_.tail(m_).maxCoeff();
}

void PhaseControl::setState(const VecQ& q, const VecQ& v, ModelData& data) {
  const RbsfModel& model = *model_;
  const int m = m_, nq = model.configDim(), nu = model.controlDim(), no = layout::kObjectDim;
  c_base_range_.reset();
  u_object_range_.reset();
  model.velocityProducts(q, v, data);
  model.bias(q, v, data.bias);
  const VecQ& Q = data.bias;
  MatQQ M;
  model.massMatrix(q, M);
  n_.resize(nq, 2 * m);
  n_.leftCols(m) = data.G1;
  n_.rightCols(m) = data.T;
  h_.resize(2 * m);
  h_.head(m) = data.h_n;
  h_.tail(m) = data.h_t;

  // ---- Phase C: the constrained accelerations as an affine function of (theta'', s'').
  c_ok_ = m >= 2 && (n_.transpose() * v).cwiseAbs().maxCoeff() <= options_.slip_speed;
  if (c_ok_) {
    MatrixXd C = MatrixXd::Zero(2 * m + 2, nq);
    C.topRows(2 * m) = n_.transpose();
    C(2 * m, layout::kTheta) = 1.0;
    for (int i = 0; i < m; ++i) C(2 * m + 1, layout::stroke(i)) = 1.0 / m;
    MatrixXd rhs = MatrixXd::Zero(2 * m + 2, 3);
    rhs.col(0).head(2 * m) = -h_;
    rhs(2 * m, 1) = 1.0;
    rhs(2 * m + 1, 2) = 1.0;
    const Eigen::ColPivHouseholderQR<MatrixXd> qr(C);
    // Rank m + 4 needs two independent sticking contacts: otherwise C is not phase C.
    c_ok_ = qr.rank() == nq;
    if (c_ok_) {
      const MatrixXd sol = qr.solve(rhs);
      c_w0_ = sol.col(0);
      c_D_ = sol.rightCols(2);
    }
  }
  if (c_ok_) {
    const auto M_o = M.topLeftCorner(no, no);
    const auto M_R = M.bottomRightCorner(nu, nu);
    c_E_lam_ = n_.topRows(no);
    c_E_a_ = -M_o * c_D_.topRows(no);
    c_e_ = M_o * c_w0_.head(no) + Q.head(no);
    c_NR_ = n_.bottomRows(nu);
    c_tau0_ = M_R * c_w0_.tail(nu) + Q.tail(nu);
    c_Ta_ = M_R * c_D_.bottomRows(nu);
    // Rows: f_n >= f_min (m), then the margined cones (2m), then tau <= limit and
    // tau >= -limit (2 nu), with tau = tau0 + Ta a - N_R lambda.
    const double mu = model.cell().friction.mu_static * (1.0 - options_.friction_margin);
    const int rows = 3 * m + 2 * nu;
    c_G_lam_ = MatrixXd::Zero(rows, 2 * m);
    c_G_a_ = MatrixXd::Zero(rows, 2);
    c_g_ = VectorXd::Zero(rows);
    for (int i = 0; i < m; ++i) {
      c_G_lam_(i, i) = 1.0;
      c_g_[i] = f_min_;
      c_G_lam_(m + 2 * i, i) = mu;
      c_G_lam_(m + 2 * i, m + i) = -1.0;
      c_G_lam_(m + 2 * i + 1, i) = mu;
      c_G_lam_(m + 2 * i + 1, m + i) = 1.0;
    }
    c_G_lam_.middleRows(3 * m, nu) = c_NR_;
    c_G_a_.middleRows(3 * m, nu) = -c_Ta_;
    c_g_.segment(3 * m, nu) = c_tau0_ - solve_limit_;
    c_G_lam_.bottomRows(nu) = -c_NR_;
    c_G_a_.bottomRows(nu) = c_Ta_;
    c_g_.tail(nu) = -c_tau0_ - solve_limit_;
  }

  // ---- Phase U: dv/dt = M^-1 (B tau + G1 F_n) - M^-1 Q, linear in x = (tau, F_n).
  u_Minv_x_ = MatrixXd::Zero(nq, nu + m);
  for (int j = 0; j < nu; ++j) u_Minv_x_(layout::inputToConfig(j), j) = 1.0;
  u_Minv_x_.rightCols(m) = data.G1;
  model.applyMassInverse(q, u_Minv_x_);
  VecQ minv_q = Q;
  model.applyMassInverse(q, minv_q);
  u_acc0_ = -minv_q;
  u_E_ = data.G1.transpose() * u_Minv_x_;
  u_e_ = -(data.h_n + data.G1.transpose() * u_acc0_);
  // h_n - G1^T M^-1 Q cancels when the part rests: the solver must know the terms' size.
  u_scale_ = data.h_n.norm() + data.G1.norm() * minv_q.norm();
  u_lower_.resize(nu + m);
  u_upper_.resize(nu + m);
  u_weight_.resize(nu + m);
  u_lower_.head(nu) = -solve_limit_;
  u_upper_.head(nu) = solve_limit_;
  u_weight_.head(nu) = limit_;
  for (int i = 0; i < m; ++i) {
    u_lower_[nu + i] = f_min_;
    u_upper_[nu + i] = kInf;
    u_weight_[nu + i] = model.cell().fingers[i].force_limit;
  }
  if (options_.check_sticking) {
    minv_n_ = n_;
    model.applyMassInverse(q, minv_n_);
    k_ = n_.transpose() * minv_n_;
  }
}

PhaseControlResult PhaseControl::solveC(double theta_dd, double stroke_dd) const {
  PhaseControlResult out;
  if (!c_ok_) return out;
  const Eigen::Vector2d a(theta_dd, stroke_dd);
  const VectorXd b = c_e_ - c_E_a_ * a;
  const VectorXd g = c_g_ - c_G_a_ * a;
  // b is M_o a_o + Q_o: measure its terms, which cancel when the part falls freely.
  const double scale = c_e_.norm() + (c_E_a_ * a).norm();
  VectorXd lambda;
  if (leastNormInPolyhedron(c_E_lam_, b, c_G_lam_, g, lambda, scale) != SolveStatus::kOptimal) {
    return out;
  }
  out.feasible = true;
  out.fn = lambda.head(m_);
  out.ft = lambda.tail(m_);
  out.vdot = c_w0_ + c_D_ * a;
  out.tau = (c_tau0_ + c_Ta_ * a - c_NR_ * lambda).cwiseMax(-limit_).cwiseMin(limit_);
  return out;
}

AccelRange PhaseControl::rangeC(int which, double other) const {
  if (!c_ok_) return {};
  const int m = m_, nin = 2 * m + 2 * model_->controlDim();
  const bool fixed = !std::isnan(other);
  // Columns: lambda, a_which, and a_other unless fixed (then moved to the right-hand side:
  // a fixed LP variable would cost the simplex a row and a column).
  const int nz = 2 * m + (fixed ? 1 : 2);
  const auto G_lam = c_G_lam_.bottomRows(nin);
  const auto G_a = c_G_a_.bottomRows(nin);
  MatrixXd A(layout::kObjectDim, nz), G(nin, nz);
  A.leftCols(2 * m) = c_E_lam_;
  A.col(2 * m) = c_E_a_.col(which);
  G.leftCols(2 * m) = G_lam;
  G.col(2 * m) = G_a.col(which);
  VectorXd b = c_e_, g = c_g_.tail(nin);
  if (fixed) {
    b -= other * c_E_a_.col(1 - which);
    g -= other * G_a.col(1 - which);
  } else {
    A.col(2 * m + 1) = c_E_a_.col(1 - which);
    G.col(2 * m + 1) = G_a.col(1 - which);
  }
  VectorXd lower = VectorXd::Constant(nz, -kInf), upper = VectorXd::Constant(nz, kInf);
  lower.head(m).setConstant(f_min_);  // f_n >= f_min as bounds, not rows
  VectorXd c = VectorXd::Zero(nz);
  c[2 * m] = 1.0;
  return lpRange(c, 0.0, A, b, G, g, lower, upper);
}

AccelRange PhaseControl::rangeCBase(double stroke_dd) const { return rangeC(0, stroke_dd); }
AccelRange PhaseControl::rangeCStroke(double theta_dd) const { return rangeC(1, theta_dd); }

PhaseControlResult PhaseControl::solveU(double omega_dd, double theta_dd) const {
  const int m = m_, nu = model_->controlDim(), nx = nu + m;
  const bool base = !std::isnan(theta_dd);
  const int ne = m + 1 + (base ? 1 : 0);
  // Scaled unknowns y = W^-1 x: the least-norm y is the least normalised effort.
  MatrixXd A(ne, nx);
  VectorXd b(ne);
  A.topRows(m) = u_E_;
  b.head(m) = u_e_;
  A.row(m) = u_Minv_x_.row(layout::kPhi);
  b[m] = omega_dd - u_acc0_[layout::kPhi];
  if (base) {
    A.row(m + 1) = u_Minv_x_.row(layout::kTheta);
    b[m + 1] = theta_dd - u_acc0_[layout::kTheta];
  }
  A = A * u_weight_.asDiagonal();
  MatrixXd G = MatrixXd::Zero(2 * nu + m, nx);
  VectorXd g(2 * nu + m);
  for (int j = 0; j < nu; ++j) {
    G(2 * j, j) = 1.0;
    G(2 * j + 1, j) = -1.0;
    g[2 * j] = g[2 * j + 1] = -solve_limit_[j] / limit_[j];
  }
  for (int i = 0; i < m; ++i) {
    G(2 * nu + i, nu + i) = 1.0;
    g[2 * nu + i] = f_min_ / u_weight_[nu + i];
  }
  const double scale =
      u_scale_ + u_acc0_.norm() + std::abs(omega_dd) + (base ? std::abs(theta_dd) : 0.0);
  VectorXd y;
  PhaseControlResult out;
  if (leastNormInPolyhedron(A, b, G, g, y, scale) != SolveStatus::kOptimal) return out;
  const VectorXd x = u_weight_.cwiseProduct(y);
  out.feasible = true;
  out.tau = x.head(nu).cwiseMax(-limit_).cwiseMin(limit_);
  out.fn = x.tail(m);
  out.ft = VecC::Zero(m);
  out.vdot = u_Minv_x_ * x + u_acc0_;

  if (options_.check_sticking && c_ok_) {
    // Phase C at this tau (as solvePhaseC): K lambda = -r inside the mu_s cones.
    const VectorXd minv_u = u_Minv_x_.leftCols(nu) * out.tau;
    const VectorXd r = h_ + n_.transpose() * (minv_u + u_acc0_);
    const double mu = model_->cell().friction.mu_static;
    const MatrixXd Gc = frictionConeRows(m, mu);
    VectorXd lambda;
    const double r_scale = h_.norm() + n_.norm() * (minv_u.norm() + u_acc0_.norm());
    out.stick_feasible = leastNormInPolyhedron(k_, -r, Gc, VectorXd::Zero(3 * m), lambda,
                                               r_scale) == SolveStatus::kOptimal;
  }
  return out;
}

AccelRange PhaseControl::rangeU(int which, double other) const {
  const int rows[2] = {layout::kPhi, layout::kTheta};
  const int m = m_;
  const bool fixed = !std::isnan(other);
  MatrixXd A(m + (fixed ? 1 : 0), u_E_.cols());
  VectorXd b(A.rows());
  A.topRows(m) = u_E_;
  b.head(m) = u_e_;
  if (fixed) {
    A.row(m) = u_Minv_x_.row(rows[1 - which]);
    b[m] = other - u_acc0_[rows[1 - which]];
  }
  return lpRange(u_Minv_x_.row(rows[which]).transpose(), u_acc0_[rows[which]], A, b,
                 MatrixXd(0, A.cols()), VectorXd(0), u_lower_, u_upper_);
}

AccelRange PhaseControl::rangeUObject(double theta_dd) const { return rangeU(0, theta_dd); }
AccelRange PhaseControl::rangeUBase(double omega_dd) const { return rangeU(1, omega_dd); }

PhaseControlResult PhaseControl::sample(Phase phase, double primary, double secondary) const {
  if (phase == Phase::kC) {
    if (!c_base_range_) c_base_range_ = rangeCBase();
    const AccelRange base = *c_base_range_;
    if (!base.feasible || !finite(base)) return {};
    const double theta_dd = fromFraction(base, primary);
    const AccelRange stroke = rangeCStroke(theta_dd);
    if (!stroke.feasible || !finite(stroke)) return {};
    return solveC(theta_dd, fromFraction(stroke, secondary));
  }
  if (phase == Phase::kU) {
    if (!u_object_range_) u_object_range_ = rangeUObject();
    const AccelRange object = *u_object_range_;
    if (!object.feasible || !finite(object)) return {};
    const double omega_dd = fromFraction(object, primary);
    if (std::isnan(secondary)) return solveU(omega_dd);
    const AccelRange base = rangeUBase(omega_dd);
    if (!base.feasible || !finite(base)) return {};
    return solveU(omega_dd, fromFraction(base, secondary));
  }
  throw std::invalid_argument("PhaseControl::sample: phase must be C or U");
}

}  // namespace rbsf
