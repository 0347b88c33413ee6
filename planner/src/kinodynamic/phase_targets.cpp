#include "rbsf/planner/kinodynamic/phase_targets.h"

#include <Eigen/Dense>
#include <algorithm>

#include "rbsf/dynamics/core/small_solvers.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {
namespace {

/// The least-norm solution of G x = w from G's complete orthogonal decomposition: the steps
/// of Eigen's CompleteOrthogonalDecomposition::solve (Eigen 3.4), whose Z application takes
/// a heap work vector; here that vector is on the stack, and the arithmetic is the same.
void leastNormSolve(const Eigen::CompleteOrthogonalDecomposition<Mat3R>& cod,
                    const Eigen::Vector3d& w, VecR& x) {
  const Eigen::Index rank = cod.rank(), cols = cod.cols();
  x.setZero(cols);
  if (rank == 0) return;
  Eigen::Vector3d c = w;  // c = Q^* w
  c.applyOnTheLeft(cod.matrixQ().setLength(rank).adjoint());
  x.topRows(rank) =
      cod.matrixT().topLeftCorner(rank, rank).triangularView<Eigen::Upper>().solve(c.topRows(rank));
  if (rank < cols) {  // x = Z^* [z; 0]
    VecR temp(cols);
    for (Eigen::Index k = 0; k < rank; ++k) {
      if (k != rank - 1) x.row(k).swap(x.row(rank - 1));
      x.middleRows(rank - 1, cols - rank + 1)
          .applyHouseholderOnTheLeft(cod.matrixQTZ().row(k).tail(cols - rank).adjoint(),
                                     cod.zCoeffs()(k), &temp(0));
      if (k != rank - 1) x.row(k).swap(x.row(rank - 1));
    }
  }
  x = cod.colsPermutation() * x;  // undo the column pivoting
}

}  // namespace

PhaseTargeting::PhaseTargeting(const RbsfModel& model, double touch_distance)
    : model_(model),
      touch_distance_(touch_distance),
      data_(model.numFingers()),
      M_(MatQQ::Zero(model.configDim(), model.configDim())),
      Q_(VecQ::Zero(model.configDim())) {}

int PhaseTargeting::touching(const VecQ& q) {
  model_.updateContacts(q, data_);
  int k = 0;
  for (int i = 0; i < model_.numFingers(); ++i)
    if (data_.contacts[i].gap <= touch_distance_) ++k;
  return k;
}

void PhaseTargeting::clip(VecU& tau) const {
  const Cell& cell = model_.cell();
  const double tb = cell.base.torque_limit;
  tau[layout::kTauTheta] = std::clamp(tau[layout::kTauTheta], -tb, tb);
  for (int i = 0; i < model_.numFingers(); ++i) {
    const double f = cell.fingers[i].force_limit;
    tau[layout::fingerForce(i)] = std::clamp(tau[layout::fingerForce(i)], -f, f);
  }
}

void PhaseTargeting::mechanismTau(const VecQ& q, const VecQ& v, const VecQ& vdot,
                                  const VecQ& contact_force, VecU& tau) {
  model_.massMatrix(q, M_);
  model_.bias(q, v, Q_);
  const VecQ gen = M_ * vdot + Q_ - contact_force;
  tau.resize(model_.controlDim());
  for (int j = 0; j < model_.controlDim(); ++j) tau[j] = gen[layout::inputToConfig(j)];
  clip(tau);
}

bool PhaseTargeting::stickTau(const VecQ& q, const VecQ& v, const StickTarget& target, VecU& tau) {
  const int m = model_.numFingers();
  if (touching(q) < 2) return false;
  const double theta = q[layout::kTheta], omega = v[layout::kTheta];
  const Vec2 e = rotate(theta, Vec2(0.0, 1.0));
  double sigma_dot = 0.0;
  for (int i = 0; i < m; ++i) sigma_dot += v[layout::stroke(i)];
  sigma_dot /= m;
  const Vec2 xo(q[layout::kX], q[layout::kY]);
  const Vec2 a = target.base_accel * perp(xo) - omega * omega * xo +
                 2.0 * omega * sigma_dot * perp(e) + target.stroke_accel * e;
  VecQ vdot = VecQ::Zero(m + 4);
  vdot[layout::kX] = a.x();
  vdot[layout::kY] = a.y();
  vdot[layout::kPhi] = target.base_accel;
  vdot[layout::kTheta] = target.base_accel;
  for (int i = 0; i < m; ++i) vdot[layout::stroke(i)] = target.stroke_accel;

  // Object rows: G lambda = M_o a_o + Q_o over the touching contacts' normal and tangent
  // columns; least-norm lambda.
  const Cell& cell = model_.cell();
  const Eigen::Vector3d w(cell.object.mass * a.x(), cell.object.mass * (a.y() + cell.gravity),
                          cell.object.inertia * target.base_accel);
  Mat3R G = Mat3R::Zero(3, 2 * m);
  for (int i = 0; i < m; ++i) {
    if (data_.contacts[i].gap > touch_distance_) continue;
    G.col(2 * i) = data_.G1.col(i).head<3>();
    G.col(2 * i + 1) = data_.T.col(i).head<3>();
  }
  const Eigen::CompleteOrthogonalDecomposition<Mat3R> cod(G);
  VecR lambda;
  leastNormSolve(cod, w, lambda);
  VecQ force = VecQ::Zero(m + 4);
  for (int i = 0; i < m; ++i)
    force += data_.G1.col(i) * lambda[2 * i] + data_.T.col(i) * lambda[2 * i + 1];
  mechanismTau(q, v, vdot, force, tau);
  return tau.allFinite();
}

bool PhaseTargeting::slideTau(const VecQ& q, const VecQ& v, const SlideTarget& target, VecU& tau) {
  const int m = model_.numFingers();
  if (touching(q) < 1) return false;
  model_.velocityProducts(q, v, data_);
  const Cell& cell = model_.cell();
  // Object rows scaled to accelerations (row phi by I_o / m_o) so NNLS weighs them alike.
  const double mo = cell.object.mass, io = cell.object.inertia;
  Mat3C E = Mat3C::Zero(3, m);
  for (int i = 0; i < m; ++i) {
    if (data_.contacts[i].gap > touch_distance_) continue;
    E(0, i) = data_.G1(layout::kX, i) / mo;
    E(1, i) = data_.G1(layout::kY, i) / mo;
    E(2, i) = data_.G1(layout::kPhi, i) / io;
  }
  const Eigen::Vector3d f(target.accel_x, target.accel_y + cell.gravity, target.omega_dot);
  VecC fn(m);
  if (!solveNnls(E, f, fn)) return false;
  const Eigen::Vector3d acc = E * fn - Eigen::Vector3d(0.0, cell.gravity, 0.0);
  VecQ vdot = VecQ::Zero(m + 4);
  vdot[layout::kX] = acc[0];
  vdot[layout::kY] = acc[1];
  vdot[layout::kPhi] = acc[2];
  vdot[layout::kTheta] = target.base_accel;
  VecQ force = VecQ::Zero(m + 4);
  for (int i = 0; i < m; ++i) {
    const int k = layout::stroke(i);
    if (data_.contacts[i].gap > touch_distance_ || std::abs(data_.G1(k, i)) < 1e-9) {
      vdot[k] = target.free_stroke_accel;
      continue;
    }
    // delta_n,i = G1_i^T vdot + h_n,i = 0 solved for the stroke acceleration.
    double rest = data_.h_n[i];
    for (int j = 0; j < m + 4; ++j)
      if (j != k) rest += data_.G1(j, i) * vdot[j];
    vdot[k] = -rest / data_.G1(k, i);
    force += data_.G1.col(i) * fn[i];
  }
  mechanismTau(q, v, vdot, force, tau);
  return tau.allFinite();
}

}  // namespace rbsf::planner
