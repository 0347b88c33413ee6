#pragma once
/// \file
/// \brief The RBSF mechanism and its object: kinematics (eqs. 1-4, 13-17), mass matrix
///        and bias (eqs. 5, 6, 18) in the conventions of docs/model.md.

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/model_data.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

/// \brief Immutable model of one cell. Every evaluation writes into a ModelData and
///        allocates nothing; one model may serve many threads, each with its own data.
class RbsfModel {
 public:
  /// \throws InputError when the cell is invalid (Cell::validate()).
  explicit RbsfModel(Cell cell);

  const Cell& cell() const { return cell_; }
  const Shape& shape() const { return *cell_.object.shape; }
  /// \brief Number of fingers m.
  int numFingers() const { return m_; }
  /// \brief m + 4.
  int configDim() const { return m_ + 4; }
  /// \brief m + 1.
  int controlDim() const { return m_ + 1; }

  /// \brief Fingertip p_i = R(theta) (r_i, l_i) in the world frame [m] (eq. 2).
  Vec2 fingertip(const VecQ& q, int i) const;

  /// \brief The two non-zero columns of J_i (eq. 3): d p_i / d theta = S p_i and
  ///        d p_i / d l_i = R(theta) (0, 1).
  void fingertipJacobian(const VecQ& q, int i, Vec2& d_theta, Vec2& d_stroke) const;

  /// \brief Contact frames, gaps and the constraint columns G1 (eq. 14) and T for every
  ///        finger. xi_i is the boundary point closest to fingertip i (searched near
  ///        data.xi_hint, which is then updated). G1_i = [n_i; c_i x n_i; -J_i^T n_i] is
  ///        the gradient of the gap g_i(q) wherever the closest point is unique.
  void updateContacts(const VecQ& q, ModelData& data) const;

  /// \brief Velocity-product terms at the current contacts (call updateContacts first):
  ///        h_n,i = v^T Hess(g_i) v, so delta_n,i = G1_i^T dv/dt + h_n,i (eq. 17), and
  ///        h_t,i = (d/dt T_i)^T v, so d/dt (T_i^T v) = T_i^T dv/dt + h_t,i. Closed form
  ///        (exact for contacts with zero gap):
  ///        w = dp_i/dt - dx_o/dt - omega S c_i (tip velocity relative to the object),
  ///        h_n = omega t.w + kappa (t.w)^2 - n.(dJ_i/dt Theta') + omega t.(dp_i/dt - dx_o/dt),
  ///        h_t = -kappa (t.w)(n.w) - t.(dJ_i/dt Theta') - omega n.(dp_i/dt - dx_o/dt),
  ///        with dJ_i/dt Theta' = -theta'^2 p_i + 2 theta' l_i' S R(theta)(0, 1).
  void velocityProducts(const VecQ& q, const VecQ& v, ModelData& data) const;

  /// \brief M(q) = blockdiag(m_o, m_o, I_o, M_R) (eq. 18, docs/model.md "Dynamics").
  void massMatrix(const VecQ& q, MatQQ& M) const;

  /// \brief x <- M(q)^-1 x, column by column, in O(m) per column: M_R is an arrow matrix
  ///        (dense first row and column, diagonal otherwise), inverted by its Schur
  ///        complement I_b + sum(J_i + m_i L_i^2) on the base row.
  template <class Derived>
  void applyMassInverse(const VecQ& q, Eigen::MatrixBase<Derived>& x) const;

  /// \brief Q(q, v): gravity on the object, Coriolis, centrifugal and gravity terms of
  ///        the mechanism (docs/model.md "Dynamics").
  void bias(const VecQ& q, const VecQ& v, VecQ& Q) const;

  /// \brief Generalized input u = (0, 0, 0, tau).
  void generalizedInput(const VecU& tau, VecQ& u) const;

  /// \brief a = M(q)^-1 (u - Q): the acceleration without contact forces, from the input
  ///        tau and the bias Q of bias(). Allocation-free once a is sized.
  void freeAcceleration(const VecQ& q, const VecU& tau, const VecQ& Q, VecQ& a) const;

  /// \brief Total kinetic energy 1/2 v^T M v [J].
  double kineticEnergy(const VecQ& q, const VecQ& v) const;
  /// \brief Gravitational potential energy of object and carriages [J].
  double potentialEnergy(const VecQ& q) const;

 private:
  Cell cell_;
  int m_;
};

template <class Derived>
void RbsfModel::applyMassInverse(const VecQ& q, Eigen::MatrixBase<Derived>& x) const {
  const double inv_mo = 1.0 / cell_.object.mass;
  const double inv_io = 1.0 / cell_.object.inertia;
  double schur = cell_.base.inertia;
  for (int i = 0; i < m_; ++i) {
    const FingerParams& f = cell_.fingers[i];
    const double L = q[layout::stroke(i)] + f.com_offset;
    schur += f.inertia + f.mass * L * L;
  }
  for (int c = 0; c < x.cols(); ++c) {
    x(layout::kX, c) *= inv_mo;
    x(layout::kY, c) *= inv_mo;
    x(layout::kPhi, c) *= inv_io;
    // Eliminate the finger rows into the base row: x_theta = (y_0 - sum r_i y_i) / schur.
    double top = x(layout::kTheta, c);
    for (int i = 0; i < m_; ++i) top -= cell_.fingers[i].r * x(layout::stroke(i), c);
    const double x_theta = top / schur;
    x(layout::kTheta, c) = x_theta;
    for (int i = 0; i < m_; ++i) {
      const FingerParams& f = cell_.fingers[i];
      x(layout::stroke(i), c) = (x(layout::stroke(i), c) - f.mass * f.r * x_theta) / f.mass;
    }
  }
}

}  // namespace rbsf
