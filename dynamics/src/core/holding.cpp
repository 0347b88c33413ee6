#include "rbsf/dynamics/core/holding.h"

#include "rbsf/dynamics/core/small_solvers.h"
#include "rbsf/dynamics/core/stick_dynamics.h"

namespace rbsf {

HoldingSolution holdingTorques(const RbsfModel& model, const VecQ& q, const ModelData& data) {
  const int m = model.numFingers();
  const int nu = model.controlDim();
  const Cell& cell = model.cell();
  const double mu = cell.friction.mu_static;
  VecQ Q;
  model.bias(q, VecQ::Zero(model.configDim()), Q);

  // lambda = [F_n; F_t]; N = [G1 T] split into object rows and mechanism rows.
  Eigen::MatrixXd N(model.configDim(), 2 * m);
  N.leftCols(m) = data.G1;
  N.rightCols(m) = data.T;
  const Eigen::MatrixXd N_o = N.topRows(layout::kObjectDim);
  const Eigen::MatrixXd N_r = N.bottomRows(nu);
  const Eigen::VectorXd Q_o = Q.head(layout::kObjectDim);
  const Eigen::VectorXd Q_r = Q.tail(nu);

  Eigen::VectorXd limit(nu);
  limit[layout::kTauTheta] = cell.base.torque_limit;
  for (int i = 0; i < m; ++i) limit[layout::fingerForce(i)] = cell.fingers[i].force_limit;

  // Rows of G lambda >= h: cones (3 per contact), then tau = Q_r - N_r lambda in
  // [-limit, limit] as  N_r lambda >= Q_r - limit  and  -N_r lambda >= -Q_r - limit.
  Eigen::MatrixXd G(3 * m + 2 * nu, 2 * m);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(3 * m + 2 * nu);
  G.topRows(3 * m) = frictionConeRows(m, mu);
  G.block(3 * m, 0, nu, 2 * m) = N_r;
  h.segment(3 * m, nu) = Q_r - limit;
  G.block(3 * m + nu, 0, nu, 2 * m) = -N_r;
  h.segment(3 * m + nu, nu) = -Q_r - limit;

  HoldingSolution out;
  Eigen::VectorXd lambda;
  if (leastNormInPolyhedron(N_o, Q_o, G, h, lambda) != SolveStatus::kOptimal) return out;
  out.feasible = true;
  out.fn = lambda.head(m);
  out.ft = lambda.tail(m);
  out.tau = Q_r - N_r * lambda;
  return out;
}

}  // namespace rbsf
