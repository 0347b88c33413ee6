#pragma once
/// \file
/// \brief The terms of the equations of motion (docs/model.md "Dynamics", paper eqs. 5, 6
///        and 18) written once for any scalar: double for RbsfModel, Eigen's AutoDiffScalar
///        for the optimiser's exact derivatives (trajopt/ad_dynamics.h). Units SI; frames:
///        world frame B.
///
///   M(q) = blockdiag(m_o, m_o, I_o, M_R),  M_R: (theta, theta) baseInertia(q),
///          (theta, l_i) = (l_i, theta) m_i r_i,  (l_i, l_i) m_i;
///   Q(q, v): gravity and the velocity products (bias());
///   contact i's column for a force direction d at the point lever (from the part's COM)
///   and the tip p_i: (d, lever x d, -(S p_i) . d, -R(theta)(0, 1) . d) on
///   (x, y, phi, theta, l_i) (contactColumn(); G1_i for d = n_i, T_i for d = t_i).

#include <cmath>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::equations {

/// \brief M_theta,theta = I_b + sum_i (I_i + m_i (r_i^2 + L_i^2)), L_i = l_i + com_offset_i
///        [kg m^2]; q indexed by state_layout.h.
template <class S, class Config>
S baseInertia(const Cell& cell, const Config& q) {
  S base = S(cell.base.inertia);
  for (int i = 0; i < cell.numFingers(); ++i) {
    const FingerParams& f = cell.fingers[i];
    const S L = q[layout::stroke(i)] + f.com_offset;
    base += f.inertia + f.mass * (f.r * f.r + L * L);
  }
  return base;
}

/// \brief Q(q, v) into Q[0 .. m + 3]: m_o g0 on y; on theta sum_i 2 m_i L_i l_i' theta' +
///        m_i g0 (r_i cos theta - L_i sin theta); on l_i -m_i L_i theta'^2 + m_i g0 cos theta
///        [N, N m].
template <class S, class Config, class Out>
void bias(const Cell& cell, const Config& q, const Config& v, Out& Q) {
  using std::cos;
  using std::sin;
  const double g0 = cell.gravity;
  const S ct = cos(q[layout::kTheta]), st = sin(q[layout::kTheta]);
  const S theta_dot = v[layout::kTheta];
  Q[layout::kX] = S(0.0);
  Q[layout::kY] = S(cell.object.mass * g0);
  Q[layout::kPhi] = S(0.0);
  S q_theta = S(0.0);
  for (int i = 0; i < cell.numFingers(); ++i) {
    const FingerParams& f = cell.fingers[i];
    const S L = q[layout::stroke(i)] + f.com_offset;
    q_theta +=
        2.0 * f.mass * L * v[layout::stroke(i)] * theta_dot + f.mass * g0 * (f.r * ct - L * st);
    Q[layout::stroke(i)] = -f.mass * L * theta_dot * theta_dot + f.mass * g0 * ct;
  }
  Q[layout::kTheta] = q_theta;
}

/// \brief Contact i's generalized direction for a world direction d (file comment):
///        col = (d_x, d_y, lever x d, -(S tip) . d, -axis . d), with lever the contact point
///        from the part's COM, tip the fingertip p_i = R(theta)(r_i, l_i) and axis the
///        finger's direction R(theta)(0, 1), all in the world frame. Written on components
///        so that AutoDiff scalars are not copied into temporaries.
template <class S>
void contactColumn(const S& lever_x, const S& lever_y, const S& tip_x, const S& tip_y,
                   const S& axis_x, const S& axis_y, const S& d_x, const S& d_y, S* col) {
  col[0] = d_x;
  col[1] = d_y;
  col[2] = lever_x * d_y - lever_y * d_x;
  col[3] = -((-tip_y) * d_x + tip_x * d_y);
  col[4] = -(axis_x * d_x + axis_y * d_y);
}

}  // namespace rbsf::equations
