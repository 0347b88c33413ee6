#pragma once
/// \file
/// \brief Bounds and initial guess of the decision vector (layout in decision_layout.h).

#include <Eigen/Core>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/plan/plan.h"
#include "rbsf/trajopt/decision_layout.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

struct OptimizerSettings;

/// \brief The variables' side of the NLP.
///
/// Bounds: tau within the cell's torque and force limits; theta and strokes within their
/// limits; f_n >= 0 where the contact is on in the interval the knot starts (the last
/// knot: the last interval; Schedule::forceRole), 0 where off; f_t free where it sticks,
/// 0 otherwise (mu_k = 0, docs/model.md); q_0 = plan.q0, v_0 = 0
/// (start at rest); object pose of q_N = the goal (x, y, phi; phi taken within pi of the
/// plan's final angle), v_N = 0 (at rest at the end; with keep_end_rest the object pose of
/// every knot of a last run the part rests in, whose duration is then at least the planned
/// one); T_j within
/// [duration_min_scale, duration_max_scale] x the planned duration of run j. With
/// normal_floor > 0, the f_n of a contact the run relies on (PhaseRun::relied) at least
/// normal_floor x m_o g0. With motion_limits, the cell's motion limits (motion_limits.h) at
/// every knot: |phi'| <= angular_speed and |x'|, |y'| <= part_speed / sqrt(2) (the square
/// inside the speed's circle: bounds instead of a quadratic row, a part slower than the
/// limit in every direction).
///
/// Initial guess: the planner's trajectory at the knot times (knots spread uniformly over
/// each run's planned duration), the plan re-simulated step by step (plan.simulator.time_step): q,
/// v interpolated linearly between simulator steps; f_n and f_t of knot k the simulator's mean
/// contact forces over the knot's share of time, from the midpoint of the interval before it to
/// that of the interval after it (impulse / duration, impacts included: the collocation integrates
/// knot forces over those halves); tau the held tau of the segment the knot starts; xi the closest
/// boundary points of the tips (unwrapped along the plan); then clipped into the bounds (a force
/// where the schedule has the contact off becomes 0) and each f_t into the cone
/// |f_t| <= cone_margin mu_s f_n. Why the means: against forces sampled at the
/// knots with f_t = 0, they made the median of the object's velocity defects at the guess 4-40
/// times smaller on the default problems (measured under the trapezoidal rule,
/// docs/optimiser.md).
class DecisionVariables {
 public:
  DecisionVariables(const RbsfModel& model, const DecisionLayout& layout, const Schedule& schedule,
                    const plan::Plan& plan, const OptimizerSettings& settings);

  void bounds(Eigen::VectorXd& lower, Eigen::VectorXd& upper) const;
  Eigen::VectorXd initialGuess() const;
  /// \brief Ipopt's variable scaling (x_scaled = s x): 1 for q, v, xi; 1 / limit for tau;
  ///        1 / W_o (object weight) for f_n, f_t; 1 / planned duration for T_j. The scaled
  ///        variables are all of order one.
  Eigen::VectorXd scaling() const;
  /// \brief Planned time of knot k for the durations in z [s].
  double knotTime(const Eigen::Ref<const Eigen::VectorXd>& z, int k) const;

 private:
  const RbsfModel& model_;
  DecisionLayout layout_;
  const Schedule& schedule_;
  const plan::Plan& plan_;
  double min_scale_, max_scale_;
  /// \brief The guess before it is clipped into the bounds (the tube's centre).
  Eigen::VectorXd plannedGuess() const;

  double normal_floor_;  ///< [N]
  bool motion_limits_;
  bool keep_end_rest_;                 ///< OptimizerSettings::keep_end_rest
  double cone_;                        ///< OptimizerSettings::cone_margin
  double tube_position_, tube_angle_;  ///< [m], [rad]; 0: no tube
  Eigen::VectorXd planned_;            ///< plannedGuess()
  double goal_phi_;
};

}  // namespace rbsf::trajopt
