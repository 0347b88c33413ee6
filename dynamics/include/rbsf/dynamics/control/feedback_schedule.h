#pragma once
/// \file
/// \brief The gains of the control law (control_law.h) along one reference trajectory:
///        a time-varying LQR on the planned mode's constraint manifold, the joint PD of a
///        cell that does not see its part, and the Kalman gains of the state estimator.
///
/// Knots k = 0..K at t_k = t_0 + k D (D = gain_period rounded to whole control steps h)
/// cover the plan and `settle_time` after it, in which the reference holds the plan's
/// final pose at rest with the plan's last input (reference()). Each knot gets the contacts'
/// roles (contact_roles.h): the plan's where it states them, else those of one simulator
/// step taken from the knot's reference state under the plan's input (contacts remembered
/// sliding where the reference slips them): separated is lifted, pressed with less than
/// min_normal_force x the part's weight free, else sticking or sliding as the step did. The
/// LQR's mode follows the roles (S sticks, + and - slide, L and F are no constraint: a gain
/// that pulled on a lightly pressed contact would open it; a contact without friction
/// slides). That mode is linearised (mode_dynamics.h): A, B, F and the tangent basis P of
/// its state manifold; over the knot the step map of h is A_d = I + hA + h^2 A^2 / 2,
/// B_d = hB + h^2 AB / 2. The law keeps the contacts in their roles by the forces it
/// predicts (contact_force_qp.h, with `forces`).
///
/// LQR (part_pose sensed). Error e = x - x_ref in manifold coordinates z = P^T e, cost
/// sum z^T P^T Q P z + du^T R du with Bryson weights Q = diag(1 / tolerated error^2) and
/// R = diag(1 / (input_fraction x limit)^2); a backward Riccati recursion over every control
/// step (horizon_tail more at the last knot), the cost-to-go carried across knots by
/// P_k^T P_k+1 (the manifold changes with the mode). The gain of knot k in full
/// coordinates is K_k P_k^T: du = -K_k P_k^T e. With integral_time > 0 three states xi,
/// the integral of the part's pose error (xi' = H_p e), are appended to z and weighted by
/// 1 / ((tolerance x integral_time)^2): their gain Ki removes the steady offsets that a
/// drawn COM, mass or actuator gain leave.
///
/// Joint PD (part_pose: none). du = -K e with K non-zero only on the joints:
/// Kp_j = I_j omega_n^2, Kd_j = 2 zeta omega_n I_j, I_j the joint's effective inertia at
/// the reference start with the part held (base: M_R[0,0] + I_o + m_o |(x, y)|^2; finger:
/// m_i + m_o / m), the coupling M_R[0,i] left out.
///
/// Kalman gains. A forward covariance pass over every control step with the step maps
/// above, started from the covariance of a part resting at the start for 1 s; process
/// noise: generalized forces through the mode's constraints (F, sized as accelerations
/// M_kk x part_acceleration, part_angular_acceleration, joint_acceleration), part
/// accelerations outside the mode (slip_acceleration) and position drift (drift_speed);
/// joint measurements every step and, when sensed, part poses at the sensor's rate, with
/// the sensing's noise. Each knot keeps the joint gain of its first step and the part gain
/// a sample at its first step would get.
///
/// Tuning: the defaults hold a part balanced on two
/// frictionless tips under the default sensing; an input_fraction of 0.05 instead of 0.02
/// loses it to the camera's noise, and so does process noise three times as large (a
/// third as large loses it to model mismatch).

#include <vector>

#include <Eigen/Core>

#include "rbsf/dynamics/control/contact_force_qp.h"
#include "rbsf/dynamics/control/reference_trajectory.h"
#include "rbsf/dynamics/core/mode_dynamics.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/sensing.h"

namespace rbsf {

/// \brief The gains' knots in time and the hold after the plan.
struct GainTiming {
  double gain_period = 0.01;  ///< knot spacing D [s]
  double settle_time = 1.0;   ///< hold at rest after the plan's end [s]
  /// \brief The law's error from the reference at the start of a run decays with this time
  ///        constant instead of being corrected at once [s]; 0 corrects it at once.
  double start_blend = 0.5;
  double horizon_tail = 1.0;  ///< Riccati horizon beyond the last knot [s]
  /// \brief A hold (ControlLaw::hold()) slows the plan's time to a stop over this long [s].
  double hold_stop = 0.3;
};

/// \brief How the plan's contacts are read: which touch, which the mode relies on, when a
///        planned slider has broken loose.
struct ContactReading {
  double touch_gap = 5e-4;  ///< a reference contact within this gap touches [m]
  /// \brief The estimator's model counts a contact the plan keeps stuck (S) sliding only
  ///        above this slip [m/s]; the others at the plant's slip tolerance.
  double estimator_slip_speed = 5e-3;
  /// \brief On an exact state (the planner's nominal run) a contact the plan keeps stuck (S)
  ///        counts sliding only above this slip [m/s]. A step's sticking contact, read at
  ///        the step's end, slips by the step's change of its frame: about 1e-5 m/s in a
  ///        pivot turning 0.2 rad/s.
  double exact_slip_speed = 1e-4;
  /// \brief Without the part's pose the law takes a planned slider to have broken loose
  ///        after pulling it this long [s] (it cannot see the slip).
  double breakaway_time = 0.05;
  /// \brief A contact is a constraint of the planned mode only when the reference presses
  ///        it with at least this fraction of the part's weight.
  double min_normal_force = 0.02;
  /// \brief A finger that rises to join the part (F after L, until it is relied on) is
  ///        servoed this far past its planned stroke [m], so that it finds the part where
  ///        the part is: on the joints alone a pivot's slip is not seen, and a finger that
  ///        stops at the planned stroke is loaded by the hand-over before it touches.
  double join_reach = 0.02;
  /// \brief ... reaching out at this speed once its planned stroke has stopped [m/s], so
  ///        that it meets the part slowly.
  double join_speed = 0.02;
  /// \brief ... and pushes at most this fraction of the part's weight above its
  ///        feed-forward: it presses the part lightly, and carries the hand-over's ramp as a
  ///        force.
  double join_press = 0.01;
  /// \brief Once relied on, a joined finger's stroke error at that moment is taken off its
  ///        error and fades with this time constant [s]: the joints then carry the part back
  ///        to the plan slowly instead of pulling the finger to its planned stroke at once.
  double join_settle = 1.0;
};

/// \brief The LQR's weights: tolerated errors and inputs (Bryson's rule) and the integral
///        action on the part's pose.
struct LqrWeights {
  double position = 0.005;            ///< part x, y [m]
  double angle = 1.0 * M_PI / 180.0;  ///< part phi [rad]
  double base_angle = 0.01;           ///< theta [rad]
  double stroke = 0.002;              ///< l_i [m]
  double speed = 0.05;                ///< part x', y' [m/s]
  double angular_speed = 0.2;         ///< part phi' [rad/s]
  double base_rate = 0.2;             ///< theta' [rad/s]
  double stroke_speed = 0.05;         ///< l_i' [m/s]
  double input_fraction = 0.02;       ///< tolerated input, fraction of its limit
  /// \brief Integral action on the part's pose: the integral of its error is weighted as
  ///        an error of (position, angle) x integral_time [m s, rad s]; 0 turns it off.
  double integral_time = 0.5;
  /// \brief The law's integral is held within +- integral_limit x (position, angle) x
  ///        integral_time (anti-windup, with no integration while an input is clamped).
  double integral_limit = 3.0;
};

/// \brief The joint PD of a cell that does not see its part (part_pose: none).
struct JointServo {
  double natural_frequency = 30.0;  ///< omega_n [rad/s]
  double damping_ratio = 1.0;       ///< zeta
  /// \brief The joint-only estimate's process noise: the joints' acceleration off the
  ///        reference it expects [m/s^2, rad/s^2]. Ten times less than
  ///        ProcessNoise::joint_acceleration: the joint law runs slow plans, and a rate
  ///        estimate that follows the encoders' noise shakes the part loose.
  double servo_acceleration = 0.2;
};

/// \brief The Kalman filter's process noise: intensities [unit / s^2 / sqrt(Hz)] and drift
///        [unit / s / sqrt(Hz)].
struct ProcessNoise {
  double part_acceleration = 0.2;          ///< part x, y [m/s^2]
  double part_angular_acceleration = 1.0;  ///< part phi [rad/s^2]
  double joint_acceleration = 2.0;         ///< theta [rad/s^2], l_i [m/s^2]
  double drift_speed = 1e-4;               ///< every position [m/s or rad/s]
  /// \brief Part accelerations outside the planned mode (contacts slipping or sticking
  ///        unlike the plan), on x, y [m/s^2] and phi [rad/s^2] alike.
  double slip_acceleration = 0.01;
};

/// \brief Settings of the law and its gains, one struct per concern; defaults documented
///        in the file comment.
struct FeedbackSettings {
  GainTiming timing;            ///< knots, hold and start blend
  ContactReading contacts;      ///< the plan's contacts as the law reads them
  LqrWeights lqr;               ///< the part-pose law's weights
  JointServo servo;             ///< the joint-only law
  ProcessNoise noise;           ///< the estimator's process noise
  ContactForceSettings forces;  ///< the contact forces the law keeps (contact_force_qp.h)
};

/// \brief Gains and step maps at the knots; immutable once built, one per plan and
///        sensing, shared by any number of ControlLaw instances and threads.
class FeedbackSchedule {
 public:
  /// \brief Build every gain (off-line: allocates; tens of milliseconds for a 5 s plan).
  /// \param simulator the settings of the simulator the plan was made with; its time step
  ///        is the control period h [s].
  /// \throws InputError for a reference not ready, a non-positive step or bad settings.
  FeedbackSchedule(const RbsfModel& model, ReferenceTrajectory reference, const Sensing& sensing,
                   const SimulatorSettings& simulator, const FeedbackSettings& settings = {});

  const RbsfModel& model() const { return model_; }
  /// \brief The nominal simulator (the plan's settings): the planned modes' source.
  const Simulator& simulator() const { return simulator_; }
  /// \brief The estimator's process model: the nominal simulator with its stick/slip and
  ///        contact tolerances raised to what the measurements can tell apart
  ///        (estimator_slip_speed, when the cell has friction; 10 x the stroke noise), so
  ///        that noise in a correction does not break loose in the model a contact the
  ///        cell holds; its drift correction moves the part alone (the joints are
  ///        measured). Its steps take estimatorSlipTolerance(k): the plant's tolerance for
  ///        the contacts the plan does not keep stuck, which slide as the plant's do.
  const Simulator& estimatorSimulator() const { return estimator_; }
  const Sensing& sensing() const { return sensing_; }
  const FeedbackSettings& settings() const { return settings_; }
  double timeStep() const { return h_; }
  /// \brief True when the gains feed back the part's pose (LQR), false for joint PD.
  bool partFeedback() const { return sensing_.part_pose.present; }

  /// \brief The reference at t (reference_trajectory.h) up to the plan's end, then its
  ///        final pose at rest with the last input. Allocation-free.
  void reference(double t, ReferenceSample& out) const;
  /// \brief Start and end of the plan [s], and end of the settle hold.
  double planStart() const { return reference_.startTime(); }
  double planEnd() const { return reference_.endTime(); }
  double holdEnd() const { return reference_.endTime() + settings_.timing.settle_time; }

  /// \brief Knot whose interval holds t (clamped to the knots).
  int knotAt(double t) const;
  int numKnots() const { return static_cast<int>(Ad_.size()); }
  /// \brief Step map of one control step at knot k: 2n x 2n and 2n x (m + 1).
  const Eigen::MatrixXd& Ad(int k) const { return Ad_[k]; }
  const Eigen::MatrixXd& Bd(int k) const { return Bd_[k]; }
  /// \brief Feedback gain at knot k, (m + 1) x 2n: du = -gain (x - x_ref).
  const Eigen::MatrixXd& gain(int k) const { return K_[k]; }
  /// \brief Integral gain at knot k, (m + 1) x 3: du = -gain e - integralGain xi, xi the
  ///        integral of the part's pose error (x, y, phi) [m s, rad s]. Zero for joint PD.
  const Eigen::MatrixXd& integralGain(int k) const { return Ki_[k]; }
  /// \brief Kalman gains at knot k: joints 2n x (m + 1), part 2n x 3 (empty if not sensed).
  const Eigen::MatrixXd& jointGain(int k) const { return Lj_[k]; }
  const Eigen::MatrixXd& partGain(int k) const { return Lp_[k]; }
  /// \brief The planned modes of knot k (the LQR's).
  const ContactModes& modes(int k) const { return modes_[k]; }
  /// \brief The contacts' roles at knot k: the plan's when it states them, else those of
  ///        the simulator step from the reference (a touching contact sticks or slides the
  ///        way the reference slips it; an untouched one is lifted).
  const ContactRoles& roles(int k) const { return roles_[k]; }
  /// \brief Bit i set: finger i rises to join the part at knot k (role F, and L the last
  ///        role other than F before it; ContactReading::join_reach).
  std::uint32_t joining(int k) const { return joining_[k]; }
  /// \brief The estimator's slip tolerance per contact at knot k (Simulator::step's
  ///        `slip_tolerance`) [m/s]: its raised one where the plan keeps the tip stuck (S),
  ///        the plant's elsewhere.
  const VecC& estimatorSlipTolerance(int k) const { return estimator_slip_[k]; }

 private:
  void computeLqr(const std::vector<Eigen::MatrixXd>& tangent);
  void computePd();
  void computeKalman();
  void markJoining();
  ContactModes plannedModes(double t, SimulatorWorkspace& ws, ContactRoles& roles) const;

  const RbsfModel& model_;
  Simulator simulator_, estimator_;
  ReferenceTrajectory reference_;
  Sensing sensing_;
  double h_;
  FeedbackSettings settings_;
  int steps_per_knot_ = 10;
  double t0_ = 0.0;
  VecQ hold_q_;
  VecU hold_tau_;
  std::vector<Eigen::MatrixXd> Ad_, Bd_, F_, K_, Ki_, Lj_, Lp_;
  std::vector<ContactModes> modes_;
  std::vector<ContactRoles> roles_;
  std::vector<std::uint32_t> joining_;
  std::vector<VecC> estimator_slip_;
};

}  // namespace rbsf
