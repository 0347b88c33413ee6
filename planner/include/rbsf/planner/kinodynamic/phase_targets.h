#pragma once
/// \file
/// \brief Phase-targeted inverse dynamics, the project's one: the tau that makes a chosen
///        phase hold with chosen mechanism or object accelerations, clipped to the cell's
///        limits, for the control sampler (control_sampler.h: damped targets, the part
///        pulled back over the fingers). Fingers that do not touch are allowed: the planner's
///        states often have some lifted. Friction cones are not imposed here: the
///        propagator's decisive-modes rule refuses steps whose contacts leave their modes.
///
/// Phase C target (every touching contact sticks, paper 2.2): base acceleration alpha and
/// common stroke acceleration s. The object then moves rigidly with the base frame shifted
/// along the base y axis e = R(theta)(0, 1) by the common stroke sigma:
///   a_o = alpha S x_o - theta'^2 x_o + 2 theta' sigma' S e + s e,   phi'' = alpha,
/// with sigma' the mean stroke rate. The contact forces lambda = (f_n, f_t) of the touching
/// contacts are the least-norm solution of the object's equations G lambda = M_o a_o + Q_o;
/// tau = (M vdot + Q - G1 f_n - T f_t) on the mechanism rows.
///
/// Phase U target (every contact slides, frictionless, eq. 8): object accelerations
/// (a_x, a_y, omega') and base acceleration alpha. The normal forces are the NNLS solution
/// of G_n f_n = M_o a_o + Q_o, f_n >= 0 (the nearest achievable object acceleration is then
/// a_o = M_o^-1 (G_n f_n - Q_o)); each touching finger's stroke acceleration keeps its
/// contact closed, delta_n,i = G1_i^T vdot + h_n,i = 0 (eq. 17); fingers not touching
/// get the given free stroke acceleration. tau = (M vdot + Q - G1 f_n) on the mechanism rows.
///
/// The simulator decides what really happens with that tau (a U target whose tip motion
/// needs less friction than the cones allow keeps sticking, for example).

#include "rbsf/dynamics/core/model.h"

namespace rbsf::planner {

/// \brief Phase C target: base and common-stroke accelerations.
struct StickTarget {
  double base_accel = 0.0;    ///< alpha [rad/s^2]
  double stroke_accel = 0.0;  ///< s [m/s^2]
};

/// \brief Phase U target: object accelerations, base and free-finger accelerations.
struct SlideTarget {
  double accel_x = 0.0;            ///< [m/s^2]
  double accel_y = 0.0;            ///< [m/s^2]
  double omega_dot = 0.0;          ///< object angular acceleration [rad/s^2]
  double base_accel = 0.0;         ///< alpha [rad/s^2]
  double free_stroke_accel = 0.0;  ///< fingers not touching [m/s^2]
};

/// \brief Computes phase-targeted tau; one per thread (holds a ModelData).
class PhaseTargeting {
 public:
  /// \param touch_distance contacts with gap <= this count as touching [m]
  PhaseTargeting(const RbsfModel& model, double touch_distance);

  /// \brief tau for a phase C target; false when fewer than two contacts touch.
  bool stickTau(const VecQ& q, const VecQ& v, const StickTarget& target, VecU& tau);
  /// \brief tau for a phase U target; false when no contact touches.
  bool slideTau(const VecQ& q, const VecQ& v, const SlideTarget& target, VecU& tau);

  /// \brief Clip tau to the cell's limits |tau_theta| <= torque_limit, |tau_i| <= force_limit.
  void clip(VecU& tau) const;

 private:
  /// \brief tau = (M vdot + Q - W lambda) on the mechanism rows, clipped.
  void mechanismTau(const VecQ& q, const VecQ& v, const VecQ& vdot, const VecQ& contact_force,
                    VecU& tau);
  int touching(const VecQ& q);

  const RbsfModel& model_;
  double touch_distance_;
  ModelData data_;
  MatQQ M_;
  VecQ Q_;
};

}  // namespace rbsf::planner
