#pragma once
/// \file
/// \brief One execution of a plan as a cell runs it: the control law (control_law.h) behind
///        a guard on its inputs, a status every tick (execution_status.h), and a safe hold.
///
/// Each tick step(t, joints, tau, status):
///   - a non-finite joint reading never reaches the law: the last good one serves
///     (kFlagBadJoints) for bad_joint_time, then the part is held, still on it; before any
///     good reading the input is the plan's feed-forward. So does a finite reading that
///     jumped from its prediction (the last good reading moved on at the rate of the last
///     two)
///     by more than jump_margin times what its actuator at its limit moves the bare joint
///     in the time since (plus 10 sigma of noise): a spike (kFlagJointJump); a second
///     reading that agrees with it is taken. A non-finite t holds the last
///     input (kFlagBadTime). A non-finite part pose is dropped (kFlagBadPose).
///   - the law computes the input; were it not finite, the last good input is applied and
///     the part held (kBadOutput).
///   - the status: the deviation of the part from the law's reference, the larger of the
///     estimate's (the part as the law estimates it: under part feedback the filter's, on
///     the joints alone the plan's part moved by the strokes) and the newest part pose's
///     against the reference at its stamp, carried to the present over the pose's age by
///     its smoothed rate (poses serve the status also where the law runs on the joints
///     alone); each relied-on finger's stroke from its reference; the
///     contacts' roles from the law's tick; saturation; the pose's age; the verdict.
///   - a verdict kLeaving holds at once (hold_on_leaving), and so does a fault past its time
///     (hold_on_faults): ControlLaw::hold(), the reference stopped where the estimate is.
///
/// Real time: step(), addPartPose() and hold() allocate nothing and take no lock. One
/// executor per executing loop (it has state); the schedule it reads is shared.

#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/control/execution_status.h"
#include "rbsf/dynamics/control/feedback_schedule.h"

namespace rbsf {

/// \brief The law, its input guard, the status and the hold of one run (file comment).
class PlanExecutor {
 public:
  explicit PlanExecutor(const FeedbackSchedule& schedule, const ExecutionLimits& limits = {});

  /// \brief Start a new run (the law's reset(); the status cleared). A t earlier than the
  ///        last step's also starts one.
  void reset();
  /// \brief A part pose measured at plan time `stamp` [s] (ControlLaw::addPartPose); used by
  ///        the status whatever the law's feedback. Non-finite: dropped and flagged.
  void addPartPose(double stamp, const Pose& pose);
  /// \brief The input for [t, t + h) from the joints measured at t (tau order), and this
  ///        tick's status (also kept: status()). Allocation-free.
  void step(double t, const VecU& joints, VecU& tau);
  /// \brief Hold the part where it is from the next tick on (ControlLaw::hold()); the
  ///        status says `why`. No effect while holding.
  void hold(HoldReason why = HoldReason::kCommanded);

  const ExecutionStatus& status() const { return status_; }
  const ExecutionLimits& limits() const { return limits_; }
  const ControlLaw& law() const { return law_; }

 private:
  /// \brief The status's measures of this tick from the law and the newest pose.
  void measure(double t, const VecU& joints, bool clamped);
  /// \brief The verdict from the measures, and the holds it calls for.
  void judge(double t);
  /// \brief False for a finite reading that jumped from its prediction farther than an
  ///        actuator can move its joint in the time since the last tick (a spike); a second
  ///        reading that agrees with the first is taken (the joints did move).
  bool plausible(double t, const VecU& joints);

  const FeedbackSchedule& schedule_;
  const ExecutionLimits limits_;
  ControlLaw law_;
  ExecutionStatus status_;
  const double h_;
  VecU good_joints_, good_tau_;
  VecU gate_;            ///< each reading's largest plausible jump in one period
  VecU good_rate_;       ///< the rate of the last two good readings
  double good_t_ = 0.0;  ///< time of the last good reading
  VecU jump_;            ///< a reading held back as a jump
  double jump_t_ = 0.0;
  bool have_jump_ = false;
  bool have_joints_ = false, have_tau_ = false;
  double last_t_ = 0.0;
  bool started_ = false;
  double bad_joints_since_ = -1.0;  ///< t of the first bad reading of the present run of them
  double open_since_ = -1.0, stuck_since_ = -1.0;
  bool bad_pose_ = false;  ///< a non-finite pose since the last tick
  bool pose_new_ = false;  ///< a pose arrived since the last tick
  double pose_stamp_ = 0.0;
  Pose pose_;
  Eigen::Vector3d pose_error_ = Eigen::Vector3d::Zero();  ///< newest pose - reference (x, y, phi)
  Eigen::Vector3d pose_rate_ = Eigen::Vector3d::Zero();   ///< its smoothed rate [/s]
  double error_stamp_ = 0.0;
  bool have_error_ = false;
  ReferenceSample at_stamp_;
};

}  // namespace rbsf
