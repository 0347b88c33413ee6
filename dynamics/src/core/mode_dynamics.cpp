#include "rbsf/dynamics/core/mode_dynamics.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

namespace {

using MatRRd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;

}  // namespace

ModeDynamics::ModeDynamics(const RbsfModel& model, double regularization)
    : model_(model), regularization_(regularization) {
  if (!(regularization >= 0.0 && std::isfinite(regularization)))
    throw InputError("mode dynamics: regularization must be finite and non-negative");
}

int ModeDynamics::constraintColumns(const ContactModes& modes, const ModelData& data, MatQR& W,
                                    VecR* h) const {
  const int m = model_.numFingers(), n = model_.configDim();
  int k = 0;
  for (int i = 0; i < m; ++i)
    k += (modes[i] != ContactMode::kSeparated) + (modes[i] == ContactMode::kStick);
  W.resize(n, k);
  if (h) h->resize(k);
  int c = 0;
  for (int i = 0; i < m; ++i) {
    if (modes[i] == ContactMode::kSeparated) continue;
    W.col(c) = data.G1.col(i);
    if (h) (*h)[c] = data.h_n[i];
    ++c;
  }
  for (int i = 0; i < m; ++i) {
    if (modes[i] != ContactMode::kStick) continue;
    W.col(c) = data.T.col(i);
    if (h) (*h)[c] = data.h_t[i];
    ++c;
  }
  return k;
}

void ModeDynamics::acceleration(const VecQ& q, const VecQ& v, const VecU& tau,
                                const ContactModes& modes, ModelData& data, VecQ& vdot,
                                Eigen::VectorXd* lambda) const {
  model_.updateContacts(q, data);
  model_.velocityProducts(q, v, data);
  model_.bias(q, v, data.bias);
  model_.freeAcceleration(q, tau, data.bias, data.free_acc);
  vdot = data.free_acc;
  MatQR W, N;
  VecR h;
  const int k = constraintColumns(modes, data, W, &h);
  if (k == 0) {
    if (lambda) lambda->resize(0);
    return;
  }
  forceColumns(modes, data, v, W, N);
  model_.applyMassInverse(q, N);  // N <- M^-1 N
  MatRRd D = W.transpose() * N;
  const double eps = regularization_ * std::max(D.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  D.diagonal().array() += eps;
  VecR rhs = -(h + W.transpose() * data.free_acc);
  const VecR lam = D.partialPivLu().solve(rhs);
  vdot.noalias() += N * lam;
  if (lambda) *lambda = lam;
}

void ModeDynamics::forceColumns(const ContactModes& modes, const ModelData& data, const VecQ& v,
                                const MatQR& W, MatQR& N) const {
  // A sliding contact's normal force drags mu_k f_n against its slip.
  N = W;
  const double mu_k = model_.cell().friction.mu_kinetic;
  if (!(mu_k > 0.0)) return;
  int c = 0;
  for (int i = 0; i < model_.numFingers(); ++i) {
    if (modes[i] == ContactMode::kSeparated) continue;
    if (modes[i] == ContactMode::kSlide) {
      const double s = data.T.col(i).dot(v);
      N.col(c) -= mu_k * (s > 0.0 ? 1.0 : s < 0.0 ? -1.0 : 0.0) * data.T.col(i);
    }
    ++c;
  }
}

ModeLinearization ModeDynamics::linearize(const VecQ& q, const VecQ& v, const VecU& tau,
                                          const ContactModes& modes, double fd_step) const {
  const int m = model_.numFingers(), n = model_.configDim(), nu = model_.controlDim();
  if (q.size() != n || v.size() != n || tau.size() != nu)
    throw InputError("mode dynamics: q, v or tau sized for another cell");
  ModelData data(m);
  // The nominal closest points: every perturbed evaluation starts from them.
  data.xi_hint = VecC::Constant(m, std::numeric_limits<double>::quiet_NaN());
  model_.updateContacts(q, data);
  VecC hint(m);
  for (int i = 0; i < m; ++i) hint[i] = data.contacts[i].xi;

  ModeLinearization lin;
  VecQ vd;
  data.xi_hint = hint;
  acceleration(q, v, tau, modes, data, vd, &lin.lambda);
  lin.vdot = vd;
  stateJacobian(q, v, tau, modes, fd_step, hint, data, lin);
  MatQR W;
  const int k = inputResponse(q, v, modes, hint, data, W, lin);
  if (k == 0) {
    lin.tangent = Eigen::MatrixXd::Identity(2 * n, 2 * n);
    return lin;
  }
  lin.tangent = tangentSpace(q, v, modes, fd_step, hint, W, k, data);
  return lin;
}

void ModeDynamics::stateJacobian(const VecQ& q, const VecQ& v, const VecU& tau,
                                 const ContactModes& modes, double fd_step, const VecC& hint,
                                 ModelData& data, ModeLinearization& lin) const {
  const int n = model_.configDim();
  lin.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  lin.A.block(0, n, n, n).setIdentity();
  lin.Lx = Eigen::MatrixXd::Zero(lin.lambda.size(), 2 * n);
  Eigen::VectorXd lambda_plus, lambda_minus;
  VecQ plus, minus;
  for (int j = 0; j < 2 * n; ++j) {
    VecQ qp = q, qm = q, vp = v, vm = v;
    if (j < n) {
      qp[j] += fd_step, qm[j] -= fd_step;
    } else {
      vp[j - n] += fd_step, vm[j - n] -= fd_step;
    }
    data.xi_hint = hint;
    acceleration(qp, vp, tau, modes, data, plus, &lambda_plus);
    data.xi_hint = hint;
    acceleration(qm, vm, tau, modes, data, minus, &lambda_minus);
    lin.A.block(n, j, n, 1) = (plus - minus) / (2.0 * fd_step);
    if (lin.Lx.rows() > 0) lin.Lx.col(j) = (lambda_plus - lambda_minus) / (2.0 * fd_step);
  }
}

int ModeDynamics::inputResponse(const VecQ& q, const VecQ& v, const ContactModes& modes,
                                const VecC& hint, ModelData& data, MatQR& W,
                                ModeLinearization& lin) const {
  const int n = model_.configDim(), nu = model_.controlDim();
  data.xi_hint = hint;
  model_.updateContacts(q, data);
  model_.velocityProducts(q, v, data);
  const int k = constraintColumns(modes, data, W, nullptr);
  Eigen::MatrixXd Minv = Eigen::MatrixXd::Identity(n, n);
  model_.applyMassInverse(q, Minv);
  Eigen::MatrixXd dvdf = Minv;  // n x n: response of v' to a generalized force
  if (k > 0) {
    // The same D as acceleration(): rebuild it once at the nominal point.
    MatQR N;
    forceColumns(modes, data, v, W, N);
    model_.applyMassInverse(q, N);
    Eigen::MatrixXd D = W.transpose() * N;
    const double eps = regularization_ * std::max(D.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    D.diagonal().array() += eps;
    const Eigen::MatrixXd dlambda_df = -D.partialPivLu().solve(W.transpose() * Minv);
    dvdf += Eigen::MatrixXd(N) * dlambda_df;
    lin.Lu.resize(k, nu);
    for (int j = 0; j < nu; ++j) lin.Lu.col(j) = dlambda_df.col(layout::inputToConfig(j));
  } else {
    lin.Lu.resize(0, nu);
  }
  lin.F = Eigen::MatrixXd::Zero(2 * n, n);
  lin.F.bottomRows(n) = dvdf;
  lin.B = Eigen::MatrixXd::Zero(2 * n, nu);
  for (int j = 0; j < nu; ++j) lin.B.col(j) = lin.F.col(layout::inputToConfig(j));
  return k;
}

Eigen::MatrixXd ModeDynamics::tangentSpace(const VecQ& q, const VecQ& v, const ContactModes& modes,
                                           double fd_step, const VecC& hint, const MatQR& W, int k,
                                           ModelData& data) const {
  const int n = model_.configDim();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * k, 2 * n);
  J.block(0, 0, k, n) = W.transpose();
  J.block(k, n, k, n) = W.transpose();
  for (int j = 0; j < n; ++j) {
    VecQ qp = q, qm = q;
    qp[j] += fd_step, qm[j] -= fd_step;
    MatQR Wp, Wm;
    data.xi_hint = hint;
    model_.updateContacts(qp, data);
    constraintColumns(modes, data, Wp, nullptr);
    data.xi_hint = hint;
    model_.updateContacts(qm, data);
    constraintColumns(modes, data, Wm, nullptr);
    J.block(k, j, k, 1) = (Wp.transpose() * v - Wm.transpose() * v) / (2.0 * fd_step);
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  int rank = 0;
  for (int i = 0; i < s.size(); ++i) rank += s[i] > 1e-8 * s[0];
  return svd.matrixV().rightCols(2 * n - rank);
}

}  // namespace rbsf
