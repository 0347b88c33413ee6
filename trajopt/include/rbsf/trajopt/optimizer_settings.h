#pragma once
/// \file
/// \brief The settings of the trajectory optimiser (plan_optimizer.h): the NLP's
///        weights, bounds and options, and Ipopt's limits. A header without a library: the
///        NLP's elements, the pipeline and the controller's requests include it alone.

#include <atomic>
#include <string>

namespace rbsf::trajopt {

/// \brief Everything the optimiser can be told; defaults are the documented ones.
struct OptimizerSettings {
  int knots = 100;                  ///< collocation intervals over the whole plan (>= 2 per phase)
  double smoothness_weight = 0.01;  ///< weight of the integral of tau_dot^T W tau_dot [s^2]
  /// \brief Weight of the least-norm contact-force term (ContactForceCost) [-].
  double force_weight = 1e-3;
  double duration_min_scale = 0.5;  ///< each phase's duration within [min, max] x planned
  double duration_max_scale = 2.0;
  double cone_margin = 0.9;  ///< sticking forces kept within margin * mu_s
  /// \brief Every contact a run relies on (stated S, + or -; without stated roles every
  ///        contact that touches) pressed by at least this x m_o g0 [N/N]; 0: f_n >= 0.
  double normal_floor = 0.0;
  /// \brief The cell's motion limits at every knot (decision_variables.h): a refinement
  ///        never plans faster than the certificate allows. Off by default: the
  ///        kinodynamic plans refined are throws beyond them (their refinements are compared
  ///        with the planner's plans as they are); supportOptimizerSettings turns it on.
  bool motion_limits = false;
  /// \brief A tube around the plan (> 0: on): every knot's positions (x, y, strokes)
  ///        within tube_position [m] and angles (phi, theta) within tube_angle [rad] of the
  ///        plan's at the same share of its run. A refinement then keeps the planner's path
  ///        and what it checked along it (holding, breakaway), and changes the timing and
  ///        the forces.
  double tube_position = 0.0;
  double tube_angle = 0.0;
  /// \brief Forces where three or more contacts stick are the plant's least-norm ones
  ///        (internal_force_constraint.h): no squeeze that no actuator steers.
  bool least_norm = true;
  /// \brief Sliding contacts keep the sign of the plan's slide over each run (xi may not
  ///        move back), so the replay does not stick or reverse where the plan slides.
  bool keep_slide_direction = true;
  /// \brief With keep_slide_direction, sliding contacts move along the boundary at least
  ///        at this rate of xi, capped at half the plan's mean rate over the run [1/s];
  ///        0: no minimum.
  double min_slip_rate = 0.0;
  /// \brief true: a phase run also ends where a contact's simulated mode (stick, slide,
  ///        separated; the majority over each plan segment) changes, so a contact that lifts
  ///        off or lands inside a phase does so at a run boundary with the plan's timing;
  ///        false: one run per phase letter, each contact's role the majority over the run.
  ///        Falls back to false when `knots` is fewer than 2 per run. On 32 planner plans
  ///        true converged 28 times against 26, but with the refiner's retry 2 refinements
  ///        passed a joint-tracking replay against 4, hence off by default.
  bool split_runs_by_contact_modes = false;
  /// \brief true: where the plan ends on a run in which the part rests (PhaseRun::at_rest),
  ///        that run stays a rest of at least its planned duration: the object is at the
  ///        goal at every knot of it (its velocities, left free, stay of order h dv/dt;
  ///        fixed to 0 as well, the -30 degree refinement took 101 Ipopt iterations
  ///        instead of 25), so the refined plan ends with the part held where the planner
  ///        gave the law time to settle it. false: only the last knot is at rest, and a run
  ///        may shrink to duration_min_scale (the -30 degree support plan's 0.33 s end rest
  ///        became 0.15 s of braking, and 62 of 64 trials were still moving in the rest
  ///        window).
  bool keep_end_rest = false;
  /// \brief true: runs are cut where the plan's stated contact roles change and keep them
  ///        (schedule.h RunCut::kStatedRoles; support plans, whose roles are what the planner
  ///        checked); the plan must state every segment's roles. Overrides the split above.
  bool stated_roles = false;
  /// \brief true: the exact Hessian of the Lagrangian (nested AutoDiff and closed form);
  ///        false: Ipopt's limited-memory (L-BFGS) approximation.
  bool exact_hessian = true;
  int max_iterations = 500;          ///< Ipopt max_iter
  double tolerance = 1e-6;           ///< Ipopt tol
  double max_solve_time = 30.0;      ///< Ipopt max_wall_time [s]
  int print_level = 0;               ///< Ipopt print_level (0: silent)
  bool derivative_test = false;      ///< run Ipopt's first-order derivative checker
  std::string derivative_test_file;  ///< where the checker's output goes (Ipopt output_file)
};

}  // namespace rbsf::trajopt
