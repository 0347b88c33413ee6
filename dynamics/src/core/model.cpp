#include "rbsf/dynamics/core/model.h"

#include <cmath>

#include <Eigen/Geometry>

#include "rbsf/dynamics/core/equations.h"
#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

using layout::kPhi;
using layout::kTheta;
using layout::kX;
using layout::kY;
using layout::stroke;

RbsfModel::RbsfModel(Cell cell) : cell_(std::move(cell)), m_(cell_.numFingers()) {
  cell_.validate();
}

Vec2 RbsfModel::fingertip(const VecQ& q, int i) const {
  return rotate(q[kTheta], Vec2(cell_.fingers[i].r, q[stroke(i)]));
}

void RbsfModel::fingertipJacobian(const VecQ& q, int i, Vec2& d_theta, Vec2& d_stroke) const {
  d_theta = perp(fingertip(q, i));
  d_stroke = Vec2(-std::sin(q[kTheta]), std::cos(q[kTheta]));
}

void RbsfModel::updateContacts(const VecQ& q, ModelData& data) const {
  const Shape& s = shape();
  const Mat2 R_phi = Eigen::Rotation2Dd(q[kPhi]).toRotationMatrix();
  const Mat2 R_theta = Eigen::Rotation2Dd(q[kTheta]).toRotationMatrix();
  const Vec2 x_o(q[kX], q[kY]);
  const Vec2 d_stroke = R_theta.col(1);  // R(theta) (0, 1): every finger's direction
  data.G1.setZero();
  data.T.setZero();
  for (int i = 0; i < m_; ++i) {
    ContactFrame& c = data.contacts[i];
    c.tip = R_theta * Vec2(cell_.fingers[i].r, q[stroke(i)]);
    const Vec2 tip_local = R_phi.transpose() * (c.tip - x_o);
    const double hint = data.xi_hint[i];
    BoundaryPoint bp;
    ClosestPoint cp;
    if (std::isfinite(hint)) {
      cp = s.closestNear(tip_local, hint, &bp);
    } else {
      cp = s.closest(tip_local);
      bp = s.boundary(cp.xi);
    }
    c.xi = cp.xi;
    data.xi_hint[i] = cp.xi;
    c.gap = cp.signed_distance;
    c.lever = R_phi * bp.point;
    c.point = x_o + c.lever;
    c.normal = R_phi * bp.normal;
    c.tangent = R_phi * bp.tangent;
    c.curvature = bp.curvature;

    // The gap grows when the object moves along n (the tip recedes inside the normal
    // direction) and shrinks when the tip moves along n: G1_i = [G_i n_i; -J_i^T n_i].
    const int rows[5] = {kX, kY, kPhi, kTheta, stroke(i)};
    double n_col[5], t_col[5];
    equations::contactColumn<double>(c.lever.x(), c.lever.y(), c.tip.x(), c.tip.y(), d_stroke.x(),
                                     d_stroke.y(), c.normal.x(), c.normal.y(), n_col);
    equations::contactColumn<double>(c.lever.x(), c.lever.y(), c.tip.x(), c.tip.y(), d_stroke.x(),
                                     d_stroke.y(), c.tangent.x(), c.tangent.y(), t_col);
    for (int r = 0; r < 5; ++r) {
      data.G1(rows[r], i) = n_col[r];
      data.T(rows[r], i) = t_col[r];
    }
  }
}

void RbsfModel::velocityProducts(const VecQ& q, const VecQ& v, ModelData& data) const {
  const double theta = q[kTheta];
  const double theta_dot = v[kTheta];
  const double omega = v[kPhi];
  const Vec2 x_dot(v[kX], v[kY]);
  const Vec2 axis(-std::sin(theta), std::cos(theta));  // R(theta) (0, 1)
  for (int i = 0; i < m_; ++i) {
    const ContactFrame& c = data.contacts[i];
    const double l_dot = v[stroke(i)];
    const Vec2 tip_dot = theta_dot * perp(c.tip) + l_dot * axis;
    const Vec2 rel = tip_dot - x_dot;            // dp_i/dt - dx_o/dt
    const Vec2 w = rel - omega * perp(c.lever);  // slip of the tip over the object
    const Vec2 jdot = -theta_dot * theta_dot * c.tip + 2.0 * theta_dot * l_dot * perp(axis);
    const double wt = c.tangent.dot(w);
    const double wn = c.normal.dot(w);
    data.h_n[i] =
        omega * wt + c.curvature * wt * wt - c.normal.dot(jdot) + omega * c.tangent.dot(rel);
    // T is taken at the boundary point (not the tip), which adds omega * (n.w) off the
    // normal constraint; for a held contact (n.w = 0) both readings agree.
    data.h_t[i] = -c.curvature * wt * wn - c.tangent.dot(jdot) - omega * c.normal.dot(rel);
  }
}

void RbsfModel::massMatrix(const VecQ& q, MatQQ& M) const {
  M.setZero(m_ + 4, m_ + 4);
  M(kX, kX) = cell_.object.mass;
  M(kY, kY) = cell_.object.mass;
  M(kPhi, kPhi) = cell_.object.inertia;
  for (int i = 0; i < m_; ++i) {
    const FingerParams& f = cell_.fingers[i];
    M(kTheta, stroke(i)) = M(stroke(i), kTheta) = f.mass * f.r;
    M(stroke(i), stroke(i)) = f.mass;
  }
  M(kTheta, kTheta) = equations::baseInertia<double>(cell_, q);
}

void RbsfModel::bias(const VecQ& q, const VecQ& v, VecQ& Q) const {
  Q.resize(m_ + 4);
  equations::bias<double>(cell_, q, v, Q);
}

void RbsfModel::freeAcceleration(const VecQ& q, const VecU& tau, const VecQ& Q, VecQ& a) const {
  generalizedInput(tau, a);
  a -= Q;
  applyMassInverse(q, a);
}

void RbsfModel::generalizedInput(const VecU& tau, VecQ& u) const {
  u.setZero(layout::configDim(m_));
  for (int j = 0; j < m_ + 1; ++j) u[layout::inputToConfig(j)] = tau[j];
}

double RbsfModel::kineticEnergy(const VecQ& q, const VecQ& v) const {
  MatQQ M;
  massMatrix(q, M);
  return 0.5 * v.dot(M * v);
}

double RbsfModel::potentialEnergy(const VecQ& q) const {
  const double g0 = cell_.gravity;
  const double ct = std::cos(q[kTheta]), st = std::sin(q[kTheta]);
  double V = cell_.object.mass * g0 * q[kY];
  for (int i = 0; i < m_; ++i) {
    const FingerParams& f = cell_.fingers[i];
    V += f.mass * g0 * (f.r * st + (q[stroke(i)] + f.com_offset) * ct);
  }
  return V;
}

}  // namespace rbsf
