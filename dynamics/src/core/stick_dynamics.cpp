#include "rbsf/dynamics/core/stick_dynamics.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "rbsf/dynamics/core/small_solvers.h"

namespace rbsf {
namespace {

/// Constraint columns of the selected rows (normal rows first, then tangential rows),
/// with their velocity products and the free-motion acceleration.
struct RowSystem {
  Eigen::MatrixXd N;      // (m+4) x rows
  Eigen::MatrixXd MinvN;  // M^-1 N
  VecQ free;              // M^-1 (u - Q)
  Eigen::MatrixXd K;      // N^T M^-1 N
  Eigen::VectorXd r;      // h + N^T M^-1 (u - Q)
  double r_scale = 0.0;   // magnitude of the terms summed into r (rounding reference)
};

RowSystem buildRows(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau,
                    ModelData& data, const int* normal_rows, int n_normal, const int* tangent_rows,
                    int n_tangent) {
  model.velocityProducts(q, v, data);
  model.bias(q, v, data.bias);
  const int nq = model.configDim();
  RowSystem s;
  s.N.resize(nq, n_normal + n_tangent);
  Eigen::VectorXd h(n_normal + n_tangent);
  for (int k = 0; k < n_normal; ++k) {
    s.N.col(k) = data.G1.col(normal_rows[k]);
    h[k] = data.h_n[normal_rows[k]];
  }
  for (int k = 0; k < n_tangent; ++k) {
    s.N.col(n_normal + k) = data.T.col(tangent_rows[k]);
    h[n_normal + k] = data.h_t[tangent_rows[k]];
  }
  model.freeAcceleration(q, tau, data.bias, s.free);
  s.MinvN = s.N;
  model.applyMassInverse(q, s.MinvN);
  s.K = s.N.transpose() * s.MinvN;
  s.r = h + s.N.transpose() * s.free;
  VecQ u, minv_u, minv_q = data.bias;
  model.generalizedInput(tau, u);
  minv_u = u;
  model.applyMassInverse(q, minv_u);
  model.applyMassInverse(q, minv_q);
  // Free fall makes N^T M^-1 (u - Q) cancel to rounding: measure the terms, not the sum.
  s.r_scale = h.norm() + s.N.norm() * (minv_u.norm() + minv_q.norm());
  return s;
}

}  // namespace

Eigen::MatrixXd frictionConeRows(int m, double mu) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(3 * m, 2 * m);
  for (int i = 0; i < m; ++i) {
    G(3 * i, i) = 1.0;
    G(3 * i + 1, i) = mu;
    G(3 * i + 1, m + i) = -1.0;
    G(3 * i + 2, i) = mu;
    G(3 * i + 2, m + i) = 1.0;
  }
  return G;
}

StickSolution solvePhaseC(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau,
                          ModelData& data) {
  const int m = model.numFingers();
  const double mu = model.cell().friction.mu_static;
  int rows[kMaxFingers];
  for (int i = 0; i < m; ++i) rows[i] = i;
  const RowSystem s = buildRows(model, q, v, tau, data, rows, m, rows, m);

  const Eigen::MatrixXd G = frictionConeRows(m, mu);
  StickSolution out;
  Eigen::VectorXd lambda;
  out.feasible = leastNormInPolyhedron(s.K, -s.r, G, Eigen::VectorXd::Zero(3 * m), lambda,
                                       s.r_scale) == SolveStatus::kOptimal;
  if (!out.feasible) {
    leastNormInPolyhedron(s.K, -s.r, Eigen::MatrixXd(0, 2 * m), Eigen::VectorXd(0), lambda,
                          s.r_scale);
  }
  if (lambda.size() != 2 * m) lambda = Eigen::VectorXd::Zero(2 * m);
  out.fn = lambda.head(m);
  out.ft = lambda.tail(m);
  out.vdot = s.free + s.MinvN * lambda;
  return out;
}

StickSolution solvePhaseP(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau,
                          int pivot, ModelData& data) {
  const int m = model.numFingers();
  const double mu = model.cell().friction.mu_static;
  // Rows: [n_pivot, n_others..., t_pivot]; equalities E = {n_pivot, t_pivot}.
  int normals[kMaxFingers];
  normals[0] = pivot;
  for (int i = 0, k = 1; i < m; ++i)
    if (i != pivot) normals[k++] = i;
  const RowSystem s = buildRows(model, q, v, tau, data, normals, m, &pivot, 1);

  const int ni = m - 1;
  Eigen::Matrix2d K_ee;
  K_ee << s.K(0, 0), s.K(0, m), s.K(m, 0), s.K(m, m);
  Eigen::MatrixXd K_ei(2, ni), K_ie(ni, 2);
  K_ei.row(0) = s.K.block(0, 1, 1, ni);
  K_ei.row(1) = s.K.block(m, 1, 1, ni);
  K_ie = K_ei.transpose();
  const Eigen::Vector2d r_e(s.r[0], s.r[m]);
  const Eigen::Matrix2d K_ee_inv = K_ee.inverse();

  // Eliminate the pivot's equalities: lambda_E = -K_ee^-1 (r_E + K_ei lambda_I).
  const Eigen::MatrixXd A_red = s.K.block(1, 1, ni, ni) - K_ie * K_ee_inv * K_ei;
  const Eigen::VectorXd p_red = s.r.segment(1, ni) - K_ie * K_ee_inv * r_e;
  VecC z(ni), w(ni);
  const LcpStatus st = solveLcp(A_red, p_red, z, w);
  const Eigen::Vector2d lambda_e = -K_ee_inv * (r_e + K_ei * z);

  Eigen::VectorXd lambda(m + 1);
  lambda[0] = lambda_e[0];
  lambda.segment(1, ni) = z;
  lambda[m] = lambda_e[1];

  StickSolution out;
  out.pivot = pivot;
  out.fn = Eigen::VectorXd::Zero(m);
  out.ft = Eigen::VectorXd::Zero(m);
  for (int k = 0; k < m; ++k) out.fn[normals[k]] = lambda[k];
  out.ft[pivot] = lambda[m];
  out.vdot = s.free + s.MinvN * lambda;
  const double fn_p = lambda_e[0], ft_p = lambda_e[1];
  const double tol = 1e-9 * (1.0 + std::abs(fn_p) + std::abs(ft_p));
  out.feasible = st.solved && fn_p >= -tol && std::abs(ft_p) <= mu * fn_p + tol;
  return out;
}

}  // namespace rbsf
