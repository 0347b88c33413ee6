#pragma once
/// \file
/// \brief Joint-space tracking of a reference trajectory: PD on the mechanism joints
///        Theta = (theta, l_1..l_m) around the reference plus its feed-forward input,
///
///   tau = sat( tau_ff(t) + Kp (Theta_ref(t) - Theta) + Kd (Theta'_ref(t) - Theta') ),
///
/// Kp, Kd diagonal; sat clamps tau_theta to +-torque_limit [N m] and tau_i to
/// +-force_limit [N] (cells' limits). The object coordinates are not fed back: a cell
/// measures its joints, and the object follows through the contacts.
///
/// Default gains (a choice, documented): every joint j is treated as a decoupled second-
/// order system of inertia I_j with natural frequency omega_n and damping ratio zeta,
///   Kp_j = I_j omega_n^2,   Kd_j = 2 zeta omega_n I_j,
/// where I_j is the joint's effective inertia at a nominal configuration (usually the
/// plan's start) with the part held rigidly (phase C, the heaviest load):
///   base:     I_theta = M_R[0,0](q) + I_o + m_o |(x, y)|^2  (the part turns with the base
///             about the world origin),
///   finger i: I_i = m_i + m_o / m  (the part's mass shared equally by the fingers).
/// The off-diagonal coupling M_R[0,i] = m_i r_i is left out. Defaults omega_n = 30 rad/s,
/// zeta = 1: critically damped, ~0.15 s to settle, omega_n h = 0.03 at the simulator's
/// h = 1 ms (well inside the stable range of the 1 ms explicit controller); stiff enough
/// that a 1 mm stroke error costs ~9 N against finger forces of a few hundred N.
/// setGains() overrides them.

#include "rbsf/dynamics/model.h"
#include "rbsf/dynamics/reference_trajectory.h"

namespace rbsf {

/// \brief How the default gains are chosen (see the file comment).
struct TrackingSettings {
  double natural_frequency = 30.0;  ///< omega_n [rad/s]
  double damping_ratio = 1.0;       ///< zeta
};

/// \brief PD + feed-forward tracking of the mechanism joints; immutable after setGains().
class TrackingController {
 public:
  /// \brief Gains from `settings` and the effective inertias at `q_nominal`.
  /// \throws InputError for a non-positive frequency, a negative damping ratio or a
  ///         q_nominal of the wrong size.
  TrackingController(const RbsfModel& model, const VecQ& q_nominal,
                     const TrackingSettings& settings = {});

  /// \brief Effective inertia I_j of each joint at q (tau order; kg m^2 for the base,
  ///        kg for the fingers), as in the file comment.
  static VecU effectiveInertia(const RbsfModel& model, const VecQ& q);

  /// \brief Replace the gains (tau order: N m/rad, N m s/rad for the base; N/m, N s/m for
  ///        the fingers). \throws InputError for a wrong size, a negative or non-finite gain.
  void setGains(const VecU& kp, const VecU& kd);
  const VecU& kp() const { return kp_; }
  const VecU& kd() const { return kd_; }

  /// \brief tau for the measured (q, v) and the reference sample (its q, v, tau).
  ///        Allocation-free. \return true when a component was clamped to its limit.
  bool compute(const VecQ& q, const VecQ& v, const ReferenceSample& ref, VecU& tau) const;

  /// \brief max_j |Theta_ref,j - Theta_j| [rad for theta, m for strokes, mixed as is].
  static double jointError(const VecQ& q, const ReferenceSample& ref);

 private:
  VecU kp_, kd_, limit_;
};

}  // namespace rbsf
