#pragma once
/// \file
/// \brief Inverse dynamics by phase: the input tau that makes a chosen kinematic phase
///        (paper 2.2) hold with chosen accelerations. A planner's control sampler asks
///        for a phase and target accelerations (or fractions of the achievable range) and
///        gets a tau within the cell's limits; the simulator then decides what happens.
///
/// Units: SI throughout (m, rad, N, N m, m/s^2, rad/s^2); frames: world frame B as in
/// docs/model.md. Contact forces lambda = [F_n; F_t] act along n_i and t_i (ModelData).
///
/// **Phase C** (every contact sticks). The constrained velocities are the null space of
/// N^T, N = [G1 T]; its two directions are the base rotation and a common stroke, so the
/// accelerations are fixed by a = (theta'', s''), s'' the stroke acceleration shared by
/// every finger (omega_o'' = theta''). dv/dt = w0 + D a is the solution of
///   N^T dv/dt = -[h_n; h_t],  (dv/dt)_theta = theta'',  mean_i (dv/dt)_(l_i) = s''
/// (exact at a sticking velocity). The object rows of M dv/dt + Q = u + N lambda fix the
/// resultant of lambda (3 equations on 2m unknowns); the mechanism rows give
///   tau = M_R (dv/dt)_R + Q_R - N_R lambda,
/// affine in lambda. Constraints: f_n,i >= f_min, |f_t,i| <= mu_s (1 - friction_margin)
/// f_n,i, |tau_j| <= limit_j. **Rule: the least-norm lambda** (as holdingTorques() and
/// solvePhaseC()): the sticking forces that squeeze the part least. The C problem is
/// solved exactly by leastNormInPolyhedron().
///
/// **Phase U** (every contact slides, frictionless: mu_k = 0, F_t = 0, eq. 8). Unknowns
/// x = (tau, F_n); dv/dt = M^-1 (B tau - Q + G1 F_n) is linear in x. Constraints: every
/// contact stays closed, G1^T dv/dt + h_n = 0 (delta_n = 0, eq. 17); F_n,i >= f_min;
/// |tau_j| <= limit_j; the targets (dv/dt)_phi = omega_o'' and, if given,
/// (dv/dt)_theta = theta''. **Rule: least normalised effort**,
///   min sum_j (tau_j / limit_j)^2 + sum_i (F_n,i / force_limit_i)^2,
/// which keeps tau away from its limits. With F_n > 0 and delta_n = 0, the LCP of
/// forwardDynamicsU() has exactly this F_n as its unique solution (A is positive
/// definite), so the simulator reproduces dv/dt.
///
/// f_min = min_normal_fraction * m_o * g0 in both phases keeps every contact pressed.
/// Rounding guards: the solvers accept constraints violated by ~1e-9 of the forces' size,
/// so they see limits tightened by 1e-6 (relative) and f_min raised by 1e-6 of the largest
/// finger force limit; the returned tau is within the true limits and F_n >= f_min.
///
/// Ranges are exact linear programs (solveLp) over the same constraints. An infeasible
/// target is reported as such (feasible = false); the ranges tell what is achievable.
///
/// Cost (default cell, m = 3, CPU time): setState() ~4 us, a solve ~10 us (one small
/// least-norm problem; phase U with the sticking check ~20 us), a range ~20 us (two small
/// LPs), sample() 25-90 us at a new state. Analysis-time code: it allocates. Not
/// thread-safe (sample() caches ranges): one PhaseControl per thread.

#include <limits>
#include <optional>

#include <Eigen/Core>

#include "rbsf/dynamics/model.h"
#include "rbsf/dynamics/phase.h"

namespace rbsf {

/// \brief Safety margins of PhaseControl.
struct PhaseControlOptions {
  /// Phase C forces stay inside cones of coefficient mu_s (1 - friction_margin).
  double friction_margin = 0.2;
  /// Every normal force is at least this fraction of the part's weight m_o g0 [N/N]
  /// (with zero gravity only the rounding guard remains).
  double min_normal_fraction = 0.02;
  /// Phase C needs sticking contacts: |G1_i^T v| and |T_i^T v| at most this [m/s].
  double slip_speed = 1e-6;
  /// Phase U: also decide whether sticking would hold at the returned tau (one more
  /// least-norm solve), see PhaseControlResult::stick_feasible.
  bool check_sticking = true;
};

/// \brief Achievable interval of one acceleration [rad/s^2 or m/s^2].
struct AccelRange {
  bool feasible = false;  ///< some admissible tau exists (min, max meaningful)
  double min = 0.0;       ///< -infinity if unbounded (not expected)
  double max = 0.0;       ///< +infinity if unbounded (not expected)
};

/// \brief A tau with the motion it plans.
struct PhaseControlResult {
  bool feasible = false;  ///< the target is achievable; everything below is then set
  VecU tau;               ///< input (order of layout), within the limits [N m, N]
  VecC fn;                ///< planned normal forces [N]
  VecC ft;                ///< planned tangential forces [N]; zero in phase U
  VecQ vdot;              ///< planned accelerations, order of q
  /// Phase U with check_sticking: every contact could keep sticking at this tau (phase C
  /// fits the mu_s cones). If the contacts do not slip now, the simulator then keeps them
  /// stuck (classifyPhase() prefers C) and the part does not turn relative to the base.
  /// Always false when the contacts already slip.
  bool stick_feasible = false;
};

/// \brief Inverse dynamics for phases C and U at one state (see the file comment).
///        Usage: setState() once per state, then any number of solves and ranges.
class PhaseControl {
 public:
  static constexpr double kFree = std::numeric_limits<double>::quiet_NaN();

  /// \brief The model must outlive this object.
  explicit PhaseControl(const RbsfModel& model, const PhaseControlOptions& options = {});

  /// \brief Take the state (q, v), every finger touching. Writes data's velocity
  ///        products and bias.
  /// \pre model.updateContacts(q, data) has been called for q.
  void setState(const VecQ& q, const VecQ& v, ModelData& data);

  /// \brief Phase C with theta'' [rad/s^2] and common stroke acceleration s'' [m/s^2].
  ///        Infeasible also when phase C is not defined here: fewer than two fingers,
  ///        degenerate contacts, or slipping contacts (options.slip_speed).
  PhaseControlResult solveC(double theta_dd, double stroke_dd) const;
  /// \brief Range of theta'' in phase C with s'' fixed (kFree: any s'').
  AccelRange rangeCBase(double stroke_dd = kFree) const;
  /// \brief Range of s'' in phase C with theta'' fixed (kFree: any theta'').
  AccelRange rangeCStroke(double theta_dd = kFree) const;

  /// \brief Phase U with omega_o'' [rad/s^2] and, unless kFree, theta'' [rad/s^2].
  PhaseControlResult solveU(double omega_dd, double theta_dd = kFree) const;
  /// \brief Range of omega_o'' in phase U with theta'' fixed (kFree: any theta'').
  AccelRange rangeUObject(double theta_dd = kFree) const;
  /// \brief Range of theta'' in phase U with omega_o'' fixed (kFree: any omega_o'').
  AccelRange rangeUBase(double omega_dd = kFree) const;

  /// \brief For a control sampler: targets as fractions in [-1, 1] (clamped) of the
  ///        achievable range. Phase C: primary -> theta'' over its whole range, then
  ///        secondary -> s'' over its range at that theta''. Phase U: primary ->
  ///        omega_o'' over its whole range, then secondary -> theta'' over its range at
  ///        that omega_o'' (kFree: theta'' left to the effort rule; in phase C kFree
  ///        counts as 0). A fraction f maps onto [min, max] as f * max (f >= 0) or
  ///        -f * min (f < 0) when the range contains 0, so 0 means "no acceleration" and
  ///        the sign is the direction; otherwise linearly, -1 -> min, 1 -> max. The
  ///        extremes are pulled inside by a relative 1e-6 so the final solve is not
  ///        decided by rounding.
  /// \throws std::invalid_argument for a phase other than C or U.
  PhaseControlResult sample(Phase phase, double primary, double secondary = kFree) const;

 private:
  AccelRange rangeC(int which, double other) const;
  AccelRange rangeU(int which, double other) const;

  const RbsfModel* model_;
  PhaseControlOptions options_;
  int m_ = 0;
  double f_min_ = 0.0;  // f_min plus a rounding guard
  VecU limit_;          // the cell's |tau_j| bounds
  VecU solve_limit_;    // slightly tighter bounds the solvers see

  // Phase C in lambda (2m) and a = (theta'', s''): object rows  E_lam lambda + E_a a = e,
  // cones and tau limits  G_lam lambda + G_a a >= g; dv/dt = w0 + D a;
  // tau = tau0 + Ta a - N_R lambda.
  bool c_ok_ = false;
  Eigen::MatrixXd c_E_lam_, c_E_a_, c_G_lam_, c_G_a_, c_D_, c_Ta_, c_NR_;
  Eigen::VectorXd c_e_, c_g_, c_w0_, c_tau0_;

  // Phase U in x = (tau, F_n): closure rows  U_E x = U_e; targets omega'' = t_phi x + o_phi,
  // theta'' = t_theta x + o_theta; box lower <= x <= upper; x = W y with |y| minimised.
  Eigen::MatrixXd u_E_, u_Minv_x_;  // u_Minv_x_: dv/dt = u_Minv_x_ x + u_acc0_
  Eigen::VectorXd u_e_, u_acc0_, u_lower_, u_upper_, u_weight_;
  double u_scale_ = 0.0;  // magnitude of the terms summed into u_e_
  // Sticking check: K = N^T M^-1 N, r = h + N^T dv/dt_free.
  Eigen::MatrixXd n_, minv_n_, k_;
  Eigen::VectorXd h_;
  // sample()'s first ranges depend on the state only: a sampler drawing several controls
  // at one state pays their LPs once.
  mutable std::optional<AccelRange> c_base_range_, u_object_range_;
};

}  // namespace rbsf
