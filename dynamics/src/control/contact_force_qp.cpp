#include "rbsf/dynamics/control/contact_force_qp.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

namespace {

/// Lever that turns a moment into a force for the motion weights [m].
constexpr double kMomentLever = 0.1;
/// A slip slower than this has no direction [m/s].
constexpr double kNoSlip = 1e-6;

}  // namespace

ContactForceQp::ContactForceQp(const RbsfModel& model, const ContactForceSettings& settings)
    : model_(model),
      settings_(settings),
      data_(model.numFingers()),
      layout_{model.controlDim()},
      weight_(model.cell().object.mass * model.cell().gravity),
      qp_(model.controlDim() + 2, 0, 0) {
  fn_ = ft_ = VecC::Zero(model.numFingers());
  contacts_q_ = VecQ::Constant(model.configDim(), std::numeric_limits<double>::quiet_NaN());
  x_ = QpVecN::Zero(layout_.size());
}

void ContactForceQp::reset() {
  data_.xi_hint.setConstant(std::numeric_limits<double>::quiet_NaN());
  contacts_q_.setConstant(std::numeric_limits<double>::quiet_NaN());
}

const ModelData& ContactForceQp::updateContacts(const VecQ& q) {
  if ((q.array() == contacts_q_.array()).all()) return data_;
  model_.updateContacts(q, data_);
  contacts_q_ = q;
  return data_;
}

void ContactForceQp::predict(const VecQ& q, const VecQ& v, const ContactTick& tick,
                             const VecU& demand) {
  const ContactRoles& roles = tick.roles;
  const ContactModes& estimated = tick.estimated;
  const RbsfModel& model = model_;
  const int m = model.numFingers(), nu = model.controlDim();
  const double mu_s = model.cell().friction.mu_static;
  updateContacts(q);
  model.velocityProducts(q, v, data_);
  model.bias(q, v, data_.bias);
  for (int i = 0; i < m; ++i) {
    const ContactRole r = roles[i];
    saturated_[i] = 0;
    if (estimated[i] == ContactMode::kSeparated || r == ContactRole::kLifted)
      mode_[i] = ContactMode::kSeparated;  // a lifted finger still touching lets go (its row)
    else if (slipSign(r) != 0)
      mode_[i] = tick.loose[i] ? ContactMode::kSlide : ContactMode::kStick;
    else
      mode_[i] = estimated[i];  // a tip slipping where it should stick: as it is
  }
  // A contact the plan does not rely on takes the force the plant gives it: where the demand
  // would push its least-norm force out of its cone, the plant holds it at the cone's edge
  // (its contact problem's solution), so the prediction does too.
  assemble(q, v, tick);
  for (int pass = 0; pass < m; ++pass) {
    int worst = -1;
    double excess = 0.0;
    for (int i = 0; i < m; ++i) {
      const bool free = roles[i] == ContactRole::kFree || roles[i] == ContactRole::kUnplanned;
      if (!free || mode_[i] != ContactMode::kStick) continue;
      const double fn = L_.row(normal_row_[i]).head(nu).dot(demand) + L_(normal_row_[i], nu);
      const double ft = L_.row(tangent_row_[i]).head(nu).dot(demand) + L_(tangent_row_[i], nu);
      if (std::abs(ft) - mu_s * std::max(fn, 0.0) > excess) {
        excess = std::abs(ft) - mu_s * std::max(fn, 0.0);
        worst = i;
      }
    }
    if (worst < 0) break;
    const double ft =
        L_.row(tangent_row_[worst]).head(nu).dot(demand) + L_(tangent_row_[worst], nu);
    mode_[worst] = ContactMode::kSlide;
    saturated_[worst] = ft > 0.0 ? 1 : -1;
    assemble(q, v, tick);
  }
}

void ContactForceQp::assemble(const VecQ& q, const VecQ& v, const ContactTick& tick) {
  const ContactRoles& roles = tick.roles;
  const RbsfModel& model = model_;
  const int m = model.numFingers(), n = model.configDim(), nu = model.controlDim();
  const double mu_k = model.cell().friction.mu_kinetic, mu_s = model.cell().friction.mu_static;
  int k = 0;
  for (int i = 0; i < m; ++i) normal_row_[i] = mode_[i] == ContactMode::kSeparated ? -1 : k++;
  for (int i = 0; i < m; ++i) tangent_row_[i] = mode_[i] == ContactMode::kStick ? k++ : -1;
  rows_ = k;
  W_.resize(n, k);
  N_.resize(n, k);
  hw_.resize(k);
  for (int i = 0; i < m; ++i) {
    if (normal_row_[i] >= 0) {
      W_.col(normal_row_[i]) = data_.G1.col(i);
      N_.col(normal_row_[i]) = data_.G1.col(i);
      hw_[normal_row_[i]] = data_.h_n[i];
      if (saturated_[i] != 0) {
        N_.col(normal_row_[i]) += mu_s * saturated_[i] * data_.T.col(i);  // at the edge
      } else if (mode_[i] == ContactMode::kSlide) {
        // Kinetic friction against the slip: the estimate's, or the planned one from rest.
        const double slip = data_.T.col(i).dot(v);
        const double s = std::abs(slip) > kNoSlip ? (slip > 0.0 ? 1.0 : -1.0) : slipSign(roles[i]);
        N_.col(normal_row_[i]) -= mu_k * s * data_.T.col(i);
      }
    }
    if (tangent_row_[i] >= 0) {
      W_.col(tangent_row_[i]) = data_.T.col(i);
      N_.col(tangent_row_[i]) = data_.T.col(i);
      hw_[tangent_row_[i]] = data_.h_t[i];
    }
  }

  // Free acceleration M^-1 (u - Q) = af0 + Mu tau; Mp: M^-1 on the part's coordinates.
  Mu_.setZero(n, nu);
  for (int j = 0; j < nu; ++j) Mu_(layout::inputToConfig(j), j) = 1.0;
  model.applyMassInverse(q, Mu_);
  Mp_.setZero(n, layout::kObjectDim);
  for (int c = 0; c < layout::kObjectDim; ++c) Mp_(c, c) = 1.0;
  model.applyMassInverse(q, Mp_);
  af0_ = -data_.bias;
  model.applyMassInverse(q, af0_);
  a0_ = af0_;
  B_ = Mu_;
  L_.resize(k, nu + 4);
  if (k == 0) return;

  // (W^T M^-1 N) lambda = -(h_W + W^T a_f) by the least-norm rule: (D + eps I)^-1 twice,
  // the second solve removing what rounding put into D's null space (simulator.h).
  MinvN_ = N_;
  model.applyMassInverse(q, MinvN_);
  D_.noalias() = W_.transpose() * MinvN_;
  De_ = D_;
  De_.diagonal().array() += 1e-9 * std::max(D_.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  lu_.compute(De_);
  L_.leftCols(nu).noalias() = -(W_.transpose() * Mu_);
  L_.col(nu).noalias() = -(W_.transpose() * af0_);
  L_.col(nu) -= hw_;
  L_.rightCols(3).noalias() = -(W_.transpose() * Mp_);
  L1_ = lu_.solve(L_);
  L_.noalias() = D_ * L1_;
  L1_ = lu_.solve(L_);
  L_ = L1_;
  a0_.noalias() += MinvN_ * L_.col(nu);
  B_.noalias() += MinvN_ * L_.leftCols(nu);
}

/// \brief Writes the QP's inequality rows one after the other, each on the forces lambda
///        (through L_: lambda = L tau + constant + d/d f of the uncertain gravity) or on an
///        acceleration (through B_ and a0_).
class ContactForceQp::RowWriter {
 public:
  RowWriter(ContactForceQp& qp, const VecU& demand, double dmoment)
      : o_(qp),
        A_(qp.qp_.A),
        b_(qp.qp_.b),
        demand_(demand),
        dmoment_(dmoment),
        nu_(qp.model_.controlDim()) {}

  /// Row c . lambda + constant >= -slack W (its violation, sigma or pi).
  void force(const VecR& c, double constant, int slack) {
    A_.row(r_).head(nu_).noalias() = c.transpose() * o_.L_.leftCols(nu_);
    A_(r_, slack) = o_.weight_;
    b_[r_] = -(c.dot(o_.L_.col(nu_)) + constant);
    ++r_;
  }
  /// Row c . lambda + constant >= R + rho W (its margin beyond the robust one R).
  void margin(const VecR& c, double constant) {
    const Uncertainty& un = o_.model_.cell().uncertainty;
    const double weight = o_.weight_;
    double robust = std::abs(c.dot(o_.L_.col(nu_ + 2))) * weight * un.mass +
                    std::abs(c.dot(o_.L_.col(nu_ + 3))) * dmoment_;
    for (int j = 0; j < nu_; ++j)
      robust += std::abs(c.dot(o_.L_.col(j))) * std::abs(demand_[j]) * un.actuator_gain;
    robust = std::min(robust, o_.settings_.robust_cap * weight);
    A_.row(r_).head(nu_).noalias() = c.transpose() * o_.L_.leftCols(nu_);
    A_(r_, o_.layout_.margin()) = -weight;
    b_[r_] = -(c.dot(o_.L_.col(nu_)) + constant) + robust;
    ++r_;
  }
  /// Row on an acceleration w . dv/dt + constant >= 0 (times the part's mass), violable.
  void motion(const VecQ& w, double constant) {
    const double mass = o_.model_.cell().object.mass;
    A_.row(r_).head(nu_).noalias() = mass * (w.transpose() * o_.B_);
    A_(r_, o_.layout_.violation()) = o_.weight_;
    b_[r_] = -mass * (w.dot(o_.a0_) + constant);
    ++r_;
  }
  /// Row sign x_col >= bound.
  void bound(int col, double sign, double bound) {
    A_(r_, col) = sign;
    b_[r_++] = bound;
  }
  int rows() const { return r_; }

 private:
  const ContactForceQp& o_;
  QpMatIN& A_;
  QpVecI& b_;
  const VecU& demand_;
  const double dmoment_;  // the worst first-order change of a moment [N m]
  const int nu_;
  int r_ = 0;
};

void ContactForceQp::setCost(const VecQ& q, const VecU& demand) {
  const int n = model_.configDim(), nu = model_.controlDim();
  const ContactForceSettings& s = settings_;
  const QpLayout& lay = layout_;
  // The motion's generalized-force error per part weight, then rho and sigma.
  model_.massMatrix(q, M_);
  SB_.resize(n, nu);
  for (int c = 0; c < n; ++c) {
    const bool moment = c == layout::kPhi || c == layout::kTheta;
    SB_.row(c) = (M_(c, c) / (weight_ * (moment ? kMomentLever : 1.0))) * B_.row(c);
  }
  qp_.H.topLeftCorner(nu, nu).noalias() = SB_.transpose() * SB_;
  qp_.H.topLeftCorner(nu, nu).diagonal().array() += s.input_regularization / (weight_ * weight_);
  qp_.g.head(nu).noalias() = -qp_.H.topLeftCorner(nu, nu) * demand;
  qp_.H(lay.margin(), lay.margin()) = 1e-3;
  qp_.g[lay.margin()] = -s.margin_reward;
  qp_.H(lay.violation(), lay.violation()) = 1.0;
  qp_.g[lay.violation()] = s.violation_penalty;
  qp_.H(lay.shortfall(), lay.shortfall()) = 1.0;
  qp_.g[lay.shortfall()] = s.shortfall_penalty;
}

void ContactForceQp::motionDemand(const VecQ& q, const VecQ& vdot, VecU& demand) {
  const int n = model_.configDim(), nu = model_.controlDim();
  model_.massMatrix(q, M_);
  SB_.resize(n, nu);
  VecQ target(n);
  for (int c = 0; c < n; ++c) {
    const bool moment = c == layout::kPhi || c == layout::kTheta;
    const double scale = M_(c, c) / (weight_ * (moment ? kMomentLever : 1.0));
    SB_.row(c) = scale * B_.row(c);
    target[c] = scale * (vdot[c] - a0_[c]);
  }
  MatQQ H = SB_.transpose() * SB_;
  H.diagonal().array() += settings_.input_regularization / (weight_ * weight_);
  demand = H.ldlt().solve(SB_.transpose() * target);
}

bool ContactForceQp::solveForMotion(const VecQ& q, const VecQ& v, const ContactTick& tick,
                                    const VecQ& vdot, VecU& tau, const VecU& feedforward) {
  VecU demand = VecU::Zero(model_.controlDim());
  if (feedforward.size() == demand.size()) {
    demand = feedforward;
  } else {
    predict(q, v, tick, demand);
    motionDemand(q, vdot, demand);
  }
  solve(q, v, tick, demand, tau);
  // Again with the input chosen as the demand: its internal forces keep the rows where they
  // can, so a free contact is predicted saturated only where the rows cannot keep it in its
  // cone (the least-norm demand's internal forces are none).
  demand = tau;
  return solve(q, v, tick, demand, tau);
}

double ContactForceQp::motionError(const VecU& tau, const VecQ& vdot) const {
  const VecQ a = predictedAcceleration(tau) - vdot;
  double worst = 0.0;
  for (int c = 0; c < a.size(); ++c) {
    const bool moment = c == layout::kPhi || c == layout::kTheta;
    worst = std::max(worst, M_(c, c) * std::abs(a[c]) / (weight_ * (moment ? kMomentLever : 1.0)));
  }
  return worst;
}

void ContactForceQp::contactRows(RowWriter& w, int i, const VecQ& v, const ContactTick& tick,
                                 VecR& c) const {
  const ContactForceSettings& s = settings_;
  const double mu_s = model_.cell().friction.mu_static;
  const ContactRole role = tick.roles[i];
  const int sgn = slipSign(role);
  if (role == ContactRole::kLifted) {
    const double a = s.clearance_rate, gap = data_.contacts[i].gap;
    w.motion(data_.G1.col(i),
             data_.h_n[i] + 2.0 * a * data_.G1.col(i).dot(v) + a * a * (gap - s.clearance));
    return;
  }
  if (normal_row_[i] < 0) return;
  const bool relied = role != ContactRole::kFree && role != ContactRole::kUnplanned;
  c.setZero();
  c[normal_row_[i]] = 1.0;
  w.force(c, relied ? -s.normal_floor * weight_ : 0.0, layout_.violation());
  if (relied) w.margin(c, -s.normal_floor * weight_);
  if (mode_[i] == ContactMode::kStick && sgn == 0) {
    for (const double side : {1.0, -1.0}) {
      c.setZero();
      c[normal_row_[i]] = (relied ? s.friction_limit : 1.0) * mu_s;
      c[tangent_row_[i]] = side;
      w.force(c, 0.0, layout_.violation());
      if (!relied) continue;
      c[normal_row_[i]] = s.friction_use * mu_s;
      w.margin(c, 0.0);
    }
  } else if (mode_[i] == ContactMode::kStick) {
    c.setZero();
    c[normal_row_[i]] = -s.breakaway * mu_s;
    c[tangent_row_[i]] = -sgn;
    w.force(c, -s.pull_margin * weight_, layout_.shortfall());
  } else if (sgn != 0) {
    const double slip = sgn * data_.T.col(i).dot(v);
    const double floor = tick.slip_floor.size() > i ? tick.slip_floor[i] : s.slip_speed;
    if (floor > 0.0)
      w.motion(sgn * data_.T.col(i), sgn * data_.h_t[i] - s.slip_gain * (floor - slip));
  }
}

void ContactForceQp::buildQp(const VecQ& q, const VecQ& v, const ContactTick& tick,
                             const VecU& demand) {
  const Cell& cell = model_.cell();
  const int m = model_.numFingers(), nu = model_.controlDim();
  const QpLayout& lay = layout_;
  // Rows: at most two per condition, three conditions per contact, the input box and the
  // bounds of rho, sigma and pi.
  qp_.resize(lay.size(), 0, 6 * m + 2 * nu + 4);
  setCost(q, demand);

  // The worst first-order change of a row from the cell's stated uncertainty.
  const double phi = q[layout::kPhi];
  const double dmoment =
      weight_ * cell.uncertainty.com * (std::abs(std::cos(phi)) + std::abs(std::sin(phi)));
  RowWriter w(*this, demand, dmoment);
  VecR c(rows_);
  for (int i = 0; i < m; ++i) contactRows(w, i, v, tick, c);
  for (int j = 0; j < nu; ++j) {
    w.bound(j, 1.0, -cell.inputLimit(j));
    w.bound(j, -1.0, -cell.inputLimit(j));
  }
  w.bound(lay.margin(), -1.0, -settings_.margin_cap);
  w.bound(lay.violation(), 1.0, 0.0);
  w.bound(lay.shortfall(), 1.0, 0.0);
  // The rows left over stay 0 x >= -1: never active.
  for (int j = w.rows(); j < qp_.numInequalities(); ++j) qp_.b[j] = -1.0;
}

bool ContactForceQp::solve(const VecQ& q, const VecQ& v, const ContactTick& tick,
                           const VecU& demand, VecU& tau) {
  const int m = model_.numFingers(), nu = model_.controlDim();
  const ContactRoles& roles = tick.roles;
  predict(q, v, tick, demand);
  buildQp(q, v, tick, demand);
  qp_.solve();
  x_ = qp_.x;
  tau.resize(nu);
  const Cell& cell = model_.cell();
  for (int j = 0; j < nu; ++j) tau[j] = std::clamp(x_[j], -cell.inputLimit(j), cell.inputLimit(j));

  fn_.setZero(m);
  ft_.setZero(m);
  use_ = 0.0;
  const double mu_s = cell.friction.mu_static;
  for (int i = 0; i < m; ++i) {
    if (normal_row_[i] >= 0)
      fn_[i] = L_.row(normal_row_[i]).head(nu).dot(tau) + L_(normal_row_[i], nu);
    if (tangent_row_[i] < 0) continue;
    ft_[i] = L_.row(tangent_row_[i]).head(nu).dot(tau) + L_(tangent_row_[i], nu);
    if (roles[i] == ContactRole::kStick && fn_[i] > 0.0)
      use_ = std::max(use_, std::abs(ft_[i]) / (mu_s * fn_[i]));
  }
  return qp_.status == QpStatus::kOptimal && violation() <= 1e-6;
}

}  // namespace rbsf
