#pragma once
/// \file
/// \brief The control law: the one feedback that executes a plan on a cell, used by the
///        certificate's trials, rbsf-replay, the controller facade and the example loop.
///
/// Every control period [t, t + h) it takes the joints measured at t (theta, l_1..l_m, no
/// velocities) and any part poses measured since (timestamped, late by the sensor's
/// latency), estimates the state and chooses the input by the contact forces it produces:
///
///   demand  tau_d = tau_ff(t + h/2) - K(t) e - K_i(t) xi,   e = x_hat(t) - x_ref(t),
///   input   tau = the contact-force QP at x_hat for the roles of the plan at t, closest in
///           motion to tau_d (contact_force_qp.h),
///
/// tau_ff and x_ref from the plan's reference (feedback_schedule.h: held at rest after the
/// plan's end), K the schedule's gain: a time-varying LQR on the planned mode's manifold
/// when the cell senses the part, the joint PD of a cell that does not; xi the integral of
/// the estimated part pose error (x, y, phi), accumulated only while no input is at its
/// limit and held within the schedule's integral_limit (anti-windup). The error a run starts
/// with is not corrected at once but decays with start_blend: the reference is joined where
/// the cell starts (a part placed a millimetre off is not jerked back).
///
/// The QP keeps every contact in its role: sticking ones inside their cones with margins
/// for the cell's stated uncertainty, the squeeze that holds best where the actuators steer
/// it; lifted fingers clear of the part; planned sliders pulled loose from rest, then
/// slipping at least at a floor. A planned slider is loose once it is seen slipping (the
/// estimate's contact memory or slip; on an exact state, its slip), and pulled again when
/// seen stuck where the reference slides it; without the part's pose it is taken loose after
/// being pulled for breakaway_time. Every input stays within the cell's limits (tau_theta
/// within +-torque_limit [N m], tau_i within +-force_limit [N]).
///
/// State estimate: an extended Kalman filter whose process model is the nominal simulator
/// itself (the schedule's: the plan's cell and simulator settings, with its contact
/// memory), so the estimate switches contact modes as the cell does, and whose gains are
/// the schedule's (feedback_schedule.h):
///   predict  x_hat <- one simulator step from x_hat under the input commanded (its
///            drift correction moves the part alone: moving the measured joints would
///            hand the joint update a residual the model made, which on a pivot grew
///            about threefold per step),
///   joints   x_hat <- x_hat + L_j (y_j - Theta_hat),
///   part     at the sample's own time t_s the correction d = L_p (z - pose_hat(t_s))
///            (angle wrapped) is carried to the present through the steps since, each
///            d <- A_d d then d <- d - L_j H_j d (the joint updates since t_s saw the
///            uncorrected estimate), and added to x_hat; then the part is moved the least
///            that closes its touching contacts' gaps, sticking contacts are re-anchored
///            where they are, and the velocity is changed the M-least that keeps the
///            contacts in their modes (touching ones closing at zero rate, sticking ones
///            not slipping): a correction must not break loose in the model a contact
///            that the cell holds (the model's contact then slides, with mu_k = 0, and
///            its part runs away).
/// The carrying is the prediction over the latency: a late pose still corrects the
/// present. A sample older than the latency plus two sample periods is dropped (counted).
///
/// A cell that does not sense its part has no use for a model of it (unobserved, the
/// model's part would drift off the fingers and corrupt the joints' prediction): its
/// estimate is each joint's error from the reference, e, and rate, e', by the steady-state
/// Kalman filter of a constant-rate error (alpha-beta; Kalata's tracking index
/// lambda = servo_acceleration h^2 / joint noise, at most 10: noise-free encoders would
/// otherwise give alpha = 1, beta = 2, the filter's marginally stable limit):
///   e <- e + h e',  r = y_j - Theta_ref,j - e,  e <- e + alpha r,  e' <- e' + beta / h r,
/// and the part is where the plan has it, offset as the strokes put it: at the start the
/// fingers of the contacts the plan starts on touch (the cell places them under the part;
/// one the plan starts lifted tells nothing of it), which fixes the part's pose and its
/// offset from the plan's (in the part's frame); later the offset pose is moved the
/// least that keeps the planned contacts on the fingers. The contact forces are predicted
/// there.
///
/// Hold (hold()): the reference is brought to rest on the plan's own path. From the hold's
/// start t_h the plan's time runs at the rate s' = 1 - (t - t_h) / hold_stop down to 0 and
/// then stays at s_h = t_h + hold_stop / 2: the reference is the plan's at s(t) with its
/// velocity times s', its input the plan's at s. So the part comes to rest where the plan
/// is a short way on, with the plan's contacts, modes and gains; sliders that the slowing
/// reference brings under the slip floor are taken as at rest (the rule that ends a run).
/// The plan's supports are quasi-static, so a state of the path at rest is held. reset()
/// (or time going back) ends the hold with the run.
///
/// Real time: compute(), hold() and addPartPose() allocate nothing; the buffers, and the
/// estimator's simulator workspace, are allocated at construction. One ControlLaw per
/// executing loop (it has state); the schedule it reads is shared.

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "rbsf/dynamics/control/contact_force_qp.h"
#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/core/placement.h"

namespace rbsf {

/// \brief Error-state vector (q, v) of up to 2 kMaxConfig entries.
using VecX = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2 * kMaxConfig, 1>;

/// \brief Estimator and law of one execution of a plan (file comment).
class ControlLaw {
 public:
  /// \brief A law on `schedule`; a part sample is applied up to the sensor's latency plus
  ///        two sample periods late (older ones are dropped).
  explicit ControlLaw(const FeedbackSchedule& schedule);

  /// \brief Start a new execution: at the first compute() the estimate is the part at the
  ///        reference's start moved the least that puts it on the fingers as measured
  ///        (the contacts the plan starts on), at rest.
  void reset();

  /// \brief A part pose measured at plan time `stamp` [s]; applied at the next compute().
  ///        At most `capacity` samples wait; more are dropped. Allocation-free.
  void addPartPose(double stamp, const Pose& pose);

  /// \brief The input for [t, t + h) from the joints measured at t (tau order, m + 1
  ///        entries). Calls are expected every h (missed periods are predicted over); a
  ///        t earlier than the last call's starts a new run (reset()).
  ///        Allocation-free. \return true when an input was clamped to its limit.
  bool compute(double t, const VecU& joints, VecU& tau);

  /// \brief Tell the estimator that the input applied over the last computed period was
  ///        `tau` instead of the law's (an override by the loop, e.g. a hold or a stop).
  void recordApplied(const VecU& tau);

  /// \brief Bring the reference to rest on the plan's path from the last compute()'s time
  ///        (file comment); no effect before the first compute() or while holding.
  ///        Allocation-free.
  void hold();
  /// \brief The plan time the reference is sampled at for control time t (t itself unless
  ///        holding), and its rate ds/dt when `rate` is given.
  double planTime(double t, double* rate = nullptr) const;
  /// \brief True from hold() until the run is reset.
  bool holding() const { return holding_; }
  /// \brief The reference the law followed at the last compute() (slowed when holding).
  const ReferenceSample& reference() const { return at_; }
  /// \brief The contacts of the last compute(): the roles it kept, the estimate's touching
  ///        and sliding, the sliders broken loose.
  const ContactTick& contacts() const { return tick_; }
  /// \brief The state the last compute() chose its input at: the estimate (on the joints
  ///        alone, the plan's part moved the least that keeps it on the planned contacts
  ///        with the strokes' offset) and its velocity.
  const VecQ& controlState() const { return q_est_; }
  const VecQ& controlVelocity() const { return v_est_; }
  /// \brief The joint-only estimate's joint errors from the reference (tau order; zero
  ///        under part feedback, whose estimate is estimate()).
  const VecU& jointErrors() const { return ej_; }

  /// \brief The same law on a known state (q, v) instead of the estimate: for analysis and
  ///        tests (what the law would do with perfect sensing). Does not touch the estimator.
  bool computeFromState(double t, const VecQ& q, const VecQ& v, VecU& tau);

  /// \brief The law's demand before clamping at the last compute() (tau order).
  const VecU& demand() const { return demand_; }
  /// \brief The state estimate at the last compute(): q and v (state_layout.h).
  void estimate(VecQ& q, VecQ& v) const;
  /// \brief Part samples dropped because they were older than the history or queued too
  ///        many at once.
  std::uint64_t droppedSamples() const { return dropped_; }

  const FeedbackSchedule& schedule() const { return schedule_; }
  /// \brief The contact-force QP of the last compute(): its predicted forces, margin and
  ///        friction use.
  const ContactForceQp& contactForces() const { return qp_; }

 private:
  /// \brief What the estimator remembers of one control step.
  struct Entry {
    double t = 0.0;
    int knot = 0;
    Eigen::Vector3d pose;  ///< estimated (x, y, phi) at t, after every correction so far
  };
  struct PartSample {
    double stamp = 0.0;
    Pose pose;
  };

  Entry& entry(long j) { return ring_[static_cast<std::size_t>(j % ring_.size())]; }
  void jointUpdate(int knot, const VecU& joints);
  void applyPartSample(const PartSample& s);
  /// \brief Move the part of q the least that closes the gaps of the contacts not
  ///        separated in `modes`.
  void closeGaps(VecQ& q, const ContactModes& modes);
  /// \brief The M-least change of the estimate's velocity that keeps its contacts' modes:
  ///        zero normal rate where touching, zero slip where sticking.
  void keepContactVelocities();
  bool control(double t, int knot, const VecX& e, const Eigen::Vector3d& xi, VecU& tau);
  bool computeJointOnly(double t, const VecU& joints, VecU& tau);
  /// \brief The reference at planTime(t), its velocity times the plan time's rate.
  void sampleReference(double t, ReferenceSample& out) const;
  int knotAt(double t) const { return schedule_.knotAt(planTime(t)); }

  const FeedbackSchedule& schedule_;
  std::unique_ptr<SimulatorWorkspace> ws_;
  ContactForceQp qp_;
  VecQ q_est_, v_est_;
  bool exact_state_ = false;
  ContactTick tick_;                          ///< the contacts' roles and state at the last tick
  std::array<double, kMaxFingers> pulled_{};  ///< how long it has been pulled loose [s]
  /// \brief A joined finger's stroke error when it came to be relied on, fading
  ///        (ContactReading::join_settle) [m].
  std::array<double, kMaxFingers> stroke_offset_{};
  std::array<double, kMaxFingers> reach_{};  ///< how far past its stroke a joining finger aims [m]
  std::uint32_t joining_ = 0;                ///< the fingers joining at the last tick
  double last_control_t_ = 0.0;
  /// \brief The demand's joining terms (ContactReading::join_reach): a joining finger
  ///        reaches past its stroke under a push cap; a joined one's error is taken off.
  void joinDemand(double t, int knot, const VecX& e);
  /// \brief The error at the start of the run, blended out (start_blend): the reference is
  ///        joined where the cell starts, not snapped to.
  void blendStart(double t, VecX& e);
  VecX start_error_;
  Eigen::Vector3d part_offset_ = Eigen::Vector3d::Zero();  ///< joint-only: part vs plan
  double start_time_ = 0.0;
  bool start_set_ = false;  ///< control() runs on an exact state (computeFromState)
  SimState state_;          ///< the estimate x_hat with the simulator's contact memory
  VecU applied_;            ///< input commanded over the last period
  std::vector<Entry> ring_;
  std::vector<PartSample> pending_;
  int num_pending_ = 0;
  long step_ = -1;  ///< index of the last computed step
  VecU demand_;
  VecX e_, d_;
  VecU alpha_, beta_;  ///< joint-only estimator gains (file comment)
  VecU ej_, dej_;      ///< joint-only estimate: joint errors and their rates
  Eigen::Vector3d xi_ = Eigen::Vector3d::Zero();  ///< integral of the part pose error
  ReferenceSample at_, mid_;
  std::uint64_t dropped_ = 0;
  bool holding_ = false;
  double hold_start_ = 0.0;  ///< t_h [s]
};

}  // namespace rbsf
