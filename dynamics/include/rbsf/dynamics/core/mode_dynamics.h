#pragma once
/// \file
/// \brief The smooth dynamics of one contact mode and their linearisation: what a
///        feedback law designed around a plan needs (feedback_schedule.h).
///
/// Within a fixed mode (each contact sticking, sliding or separated) the hybrid dynamics
/// of docs/model.md are an ODE. Touching contacts keep zero normal relative acceleration
/// (eq. 17), sticking ones also zero tangential relative acceleration:
///
///   M v' = u - Q + N lambda,      W^T v' + h_W = 0,
///
/// W = [G1_i for touching i, T_i for sticking i] (eq. 14 and its tangential twin),
/// h_W the matching velocity products (model.h), and N = W except that a sliding
/// contact's normal column is G1_i - mu_k sgn(s_i) T_i (kinetic friction against its slip
/// s_i = T_i^T v; the paper's mu_k = 0 leaves G1_i). Then
///
///   (W^T M^-1 N + eps I) lambda = -(h_W + W^T M^-1 (u - Q)),
///
/// eps = regularization x max diag(W^T M^-1 N): the least-norm rule of the simulator
/// (simulator.h), which leaves v' unique where W is rank deficient (three sticking fingers
/// carry six rows of rank five). The mode is imposed: forces are not held to their cones
/// nor to f_n >= 0 (a linearisation describes the planned mode, not its alternatives).
///
/// Linearisation of x' = f(x, tau), x = (q, v) (2n = 2(m + 4) entries, state_layout.h
/// order for each half): A = df/dx by central differences of this smooth function (each
/// closest point started from the nominal one, so every evaluation sees the same contact
/// branch), B = df/dtau and F = df/df_gen (a generalized force added to u) exactly (v' is
/// affine in both). Finite differences of the
/// time-stepping simulator would cross mode switches; these never do.
///
/// The mode's state manifold {W^T-rows of the gaps and anchors constant, W^T v = 0} has
/// tangent space null([W^T, 0; d(W^T v)/dq, W^T]); `tangent` is an orthonormal basis of
/// it (Posa, Kuindersma and Tedrake, ICRA 2016: LQR on the constraint manifold).

#include <array>

#include <Eigen/Core>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/phase.h"
#include "rbsf/dynamics/core/simulator.h"

namespace rbsf {

/// \brief Mode of every contact (finger order); entries beyond m are ignored.
using ContactModes = std::array<ContactMode, kMaxFingers>;

/// \brief Linearisation of one mode at one state (file comment). Heap matrices: built
///        off-line, never on a real-time path.
struct ModeLinearization {
  Eigen::MatrixXd A;  ///< 2n x 2n, d(q', v') / d(q, v)
  Eigen::MatrixXd B;  ///< 2n x (m + 1), d(q', v') / d tau
  /// \brief 2n x n, d(q', v') / d f for a generalized force f added to u (model errors
  ///        enter this way: through the mode's constraints, as the inputs do).
  Eigen::MatrixXd F;
  Eigen::MatrixXd tangent;  ///< 2n x r orthonormal basis of the manifold's tangent space
  Eigen::VectorXd vdot;     ///< v' at the linearisation point
  Eigen::VectorXd lambda;   ///< mode forces (rows of W) [N]
  Eigen::MatrixXd Lx;       ///< d lambda / d(q, v), rows of W x 2n
  Eigen::MatrixXd Lu;       ///< d lambda / d tau, rows of W x (m + 1), exact
};

/// \brief Smooth dynamics of one contact mode; immutable, one ModelData per thread.
class ModeDynamics {
 public:
  /// \param regularization eps relative to max diag of W^T M^-1 N (file comment).
  explicit ModeDynamics(const RbsfModel& model, double regularization = 1e-9);

  const RbsfModel& model() const { return model_; }

  /// \brief v' of the mode at (q, v, tau) (file comment); `lambda`, when given, receives
  ///        the forces per row of W (touching normals first, then sticking tangentials, in
  ///        finger order). Closest points start from data.xi_hint.
  void acceleration(const VecQ& q, const VecQ& v, const VecU& tau, const ContactModes& modes,
                    ModelData& data, VecQ& vdot, Eigen::VectorXd* lambda = nullptr) const;

  /// \brief A, B, the tangent basis, v' and lambda at (q, v, tau) (file comment);
  ///        `fd_step` is the central-difference step in every coordinate.
  ModeLinearization linearize(const VecQ& q, const VecQ& v, const VecU& tau,
                              const ContactModes& modes, double fd_step = 1e-6) const;

 private:
  /// \brief The constraint columns W (rows of the mode) at the contacts in `data`.
  int constraintColumns(const ContactModes& modes, const ModelData& data, MatQR& W, VecR* h) const;
  /// \brief The force columns N of the file comment for the constraint columns W.
  void forceColumns(const ContactModes& modes, const ModelData& data, const VecQ& v, const MatQR& W,
                    MatQR& N) const;
  /// \brief lin.A (central differences of (v, v') in (q, v), step fd_step) and lin.Lx (of
  ///        the mode's forces), every evaluation's closest points from `hint`.
  void stateJacobian(const VecQ& q, const VecQ& v, const VecU& tau, const ContactModes& modes,
                     double fd_step, const VecC& hint, ModelData& data,
                     ModeLinearization& lin) const;
  /// \brief lin.F, lin.B and lin.Lu exactly (v' = M^-1 (u - Q) + M^-1 N lambda, lambda
  ///        affine in u) and the mode's constraint columns W; returns their number k.
  int inputResponse(const VecQ& q, const VecQ& v, const ContactModes& modes, const VecC& hint,
                    ModelData& data, MatQR& W, ModeLinearization& lin) const;
  /// \brief An orthonormal basis of the tangent space of the mode's state manifold: the
  ///        null space of d(W^T q, W^T v)/d(q, v) (k > 0 constraint columns W).
  Eigen::MatrixXd tangentSpace(const VecQ& q, const VecQ& v, const ContactModes& modes,
                               double fd_step, const VecC& hint, const MatQR& W, int k,
                               ModelData& data) const;

  const RbsfModel& model_;
  double regularization_;
};

}  // namespace rbsf
