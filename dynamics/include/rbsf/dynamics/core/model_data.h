#pragma once
/// \file
/// \brief Preallocated workspace of RbsfModel (model/data split, as in Crocoddyl): every
///        buffer the kinematics and the acceleration-level dynamics write, sized once for
///        m fingers, so evaluations never allocate.

#include <array>
#include <limits>

#include "rbsf/dynamics/core/small_solvers.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief Geometry of contact i in the world frame B (docs/model.md "Contact kinematics").
struct ContactFrame {
  double xi = 0.0;         ///< boundary parameter of the point closest to the fingertip
  Vec2 tip;                ///< fingertip p_i [m]
  Vec2 point;              ///< boundary point x_o + c_i [m]
  Vec2 normal;             ///< inward normal n_i = R(phi) n(xi)
  Vec2 tangent;            ///< tangent t_i = R(phi) t(xi)
  Vec2 lever;              ///< c_i = R(phi) c(xi): COM to boundary point [m]
  double gap = 0.0;        ///< signed distance tip-to-boundary, > 0 when separated [m]
  double curvature = 0.0;  ///< boundary curvature at xi [1/m]
};

/// \brief Workspace and results of RbsfModel and forwardDynamicsU().
struct ModelData {
  /// \brief Size every buffer for m fingers (1 <= m <= kMaxFingers).
  explicit ModelData(int m);

  int m;  ///< number of fingers
  std::array<ContactFrame, kMaxFingers> contacts;
  VecC xi_hint;   ///< previous contact parameters (NaN: search globally)
  MatQC G1;       ///< normal constraint columns (eq. 14), (m+4) x m
  MatQC T;        ///< tangential constraint columns, (m+4) x m
  VecC h_n;       ///< normal velocity-product terms v^T Hess(g_i) v [m/s^2]
  VecC h_t;       ///< tangential velocity-product terms d/dt(T_i)^T v [m/s^2]
  VecQ bias;      ///< Q(q, v) (eq. 18)
  VecQ free_acc;  ///< M^-1 (u - Q): acceleration with no contact force
  MatQC MinvG1;   ///< M^-1 G1
  MatCC A;        ///< Delassus matrix G1^T M^-1 G1 (eq. 21)
  VecC p;         ///< LCP vector p (eq. 21) [m/s^2]
  VecC fn;        ///< normal forces F_n [N]
  VecC delta_n;   ///< normal relative accelerations delta_n [m/s^2]
  VecQ vdot;      ///< accelerations dv/dt, order of q
  LcpStatus lcp;  ///< pivots of the last LCP solve
};

inline ModelData::ModelData(int m_)
    : m(m_),
      xi_hint(VecC::Constant(m_, std::numeric_limits<double>::quiet_NaN())),
      G1(MatQC::Zero(m_ + 4, m_)),
      T(MatQC::Zero(m_ + 4, m_)),
      h_n(VecC::Zero(m_)),
      h_t(VecC::Zero(m_)),
      bias(VecQ::Zero(m_ + 4)),
      free_acc(VecQ::Zero(m_ + 4)),
      MinvG1(MatQC::Zero(m_ + 4, m_)),
      A(MatCC::Zero(m_, m_)),
      p(VecC::Zero(m_)),
      fn(VecC::Zero(m_)),
      delta_n(VecC::Zero(m_)),
      vdot(VecQ::Zero(m_ + 4)) {}

}  // namespace rbsf
