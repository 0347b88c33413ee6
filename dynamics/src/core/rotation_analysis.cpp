#include "rbsf/dynamics/core/rotation_analysis.h"

#include <limits>

#include "rbsf/dynamics/core/small_solvers.h"

namespace rbsf {

ContactArms contactArms(const ModelData& data, int i) {
  // Rotation-invariant, so the world-frame lever, normal and tangent give the same numbers.
  const ContactFrame& c = data.contacts[i];
  return {-c.lever.dot(c.normal), -c.lever.dot(c.tangent)};
}

bool comBetweenNormals(const ModelData& data, int i, int j) {
  return contactArms(data, i).alpha_t * contactArms(data, j).alpha_t < 0.0;
}

OmegaDotRange omegaDotRange(const RbsfModel& model, const VecQ& q, const VecQ& v, ModelData& data,
                            double tolerance) {
  const int m = model.numFingers();
  const int nu = model.controlDim();
  const Cell& cell = model.cell();
  model.velocityProducts(q, v, data);
  model.bias(q, v, data.bias);

  Eigen::MatrixXd MinvG1 = data.G1;
  model.applyMassInverse(q, MinvG1);
  VecQ minv_q = data.bias;
  model.applyMassInverse(q, minv_q);
  // M^-1 B: column j is M^-1 e_(theta + j).
  Eigen::MatrixXd MinvB = Eigen::MatrixXd::Zero(model.configDim(), nu);
  for (int j = 0; j < nu; ++j) MinvB(layout::inputToConfig(j), j) = 1.0;
  model.applyMassInverse(q, MinvB);

  // Decision vector x = (tau, F_n).
  Eigen::MatrixXd A_eq(m, nu + m);
  A_eq.leftCols(nu) = data.G1.transpose() * MinvB;
  A_eq.rightCols(m) = data.G1.transpose() * MinvG1;
  const Eigen::VectorXd b_eq = -(data.h_n.head(m) - data.G1.transpose() * minv_q);
  Eigen::VectorXd lower(nu + m), upper(nu + m);
  lower[layout::kTauTheta] = -cell.base.torque_limit;
  upper[layout::kTauTheta] = cell.base.torque_limit;
  for (int i = 0; i < m; ++i) {
    lower[layout::fingerForce(i)] = -cell.fingers[i].force_limit;
    upper[layout::fingerForce(i)] = cell.fingers[i].force_limit;
    lower[nu + i] = 0.0;
    upper[nu + i] = std::numeric_limits<double>::infinity();
  }
  // omega_o' = (M^-1 (u - Q + G1 F_n))_phi; the object rows of u vanish.
  Eigen::VectorXd c(nu + m);
  c.head(nu) = MinvB.row(layout::kPhi).transpose();
  c.tail(m) = MinvG1.row(layout::kPhi).transpose();
  const double offset = -minv_q[layout::kPhi];

  OmegaDotRange out;
  const Eigen::MatrixXd G(0, nu + m);
  const Eigen::VectorXd h(0);
  Eigen::VectorXd x;
  double value = 0.0;
  if (solveLp(c, A_eq, b_eq, G, h, lower, upper, x, &value) != SolveStatus::kOptimal) return out;
  out.feasible = true;
  out.min = value + offset;
  out.tau_min = x.head(nu);
  if (solveLp(-c, A_eq, b_eq, G, h, lower, upper, x, &value) != SolveStatus::kOptimal) return out;
  out.max = -value + offset;
  out.tau_max = x.head(nu);
  out.positive = out.max > tolerance;
  out.negative = out.min < -tolerance;
  return out;
}

}  // namespace rbsf
