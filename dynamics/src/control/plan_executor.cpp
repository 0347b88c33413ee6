#include "rbsf/dynamics/control/plan_executor.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

const char* toString(ExecutionVerdict verdict) {
  switch (verdict) {
    case ExecutionVerdict::kOnPlan:
      return "on plan";
    case ExecutionVerdict::kDegraded:
      return "degraded";
    case ExecutionVerdict::kLeaving:
      return "leaving";
    case ExecutionVerdict::kHolding:
      return "holding";
    case ExecutionVerdict::kDone:
      return "done";
  }
  return "?";
}

const char* toString(HoldReason reason) {
  switch (reason) {
    case HoldReason::kNone:
      return "none";
    case HoldReason::kLeaving:
      return "leaving";
    case HoldReason::kBadJoints:
      return "bad joints";
    case HoldReason::kStalePose:
      return "stale pose";
    case HoldReason::kBadOutput:
      return "bad output";
    case HoldReason::kCommanded:
      return "commanded";
  }
  return "?";
}

std::string flagsText(std::uint32_t flags) {
  static const char* const kWords[] = {
      "deviation",       "off the tube",          "relied-on contact open",
      "slider stuck",    "sticking tip slipping", "input at its limit",
      "stale part pose", "bad joint reading",     "bad part pose",
      "bad time",        "stroke error",          "late tick",
      "joint jump"};
  std::string out;
  for (int b = 0; b < static_cast<int>(sizeof kWords / sizeof kWords[0]); ++b)
    if ((flags >> b) & 1u) out += (out.empty() ? "; " : ", ") + std::string(kWords[b]);
  return out;
}

namespace {

bool relied(ContactRole r) { return r == ContactRole::kStick || slipSign(r) != 0; }

}  // namespace

PlanExecutor::PlanExecutor(const FeedbackSchedule& schedule, const ExecutionLimits& limits)
    : schedule_(schedule), limits_(limits), law_(schedule), h_(schedule.timeStep()) {
  const int nu = schedule.model().controlDim();
  good_joints_ = good_tau_ = jump_ = good_rate_ = VecU::Zero(nu);
  // The largest jump of a reading from its prediction in one period: what the actuator at
  // its limit moves the bare joint (its limit over its own inertia), times the margin, plus
  // the encoder's noise.
  const Cell& cell = schedule.model().cell();
  const JointSensing& js = schedule.sensing().joints;
  gate_ = VecU::Zero(nu);
  for (int j = 0; j < nu; ++j) {
    const bool base = j == layout::kTauTheta;
    const double inertia = base ? cell.base.inertia : cell.fingers[j - 1].mass;
    const double noise = base ? js.angle_noise : js.stroke_noise;
    gate_[j] = limits.jump_margin * cell.inputLimit(j) / inertia * h_ * h_ + 10.0 * noise;
  }
  schedule.reference(schedule.planStart(), at_stamp_);
}

void PlanExecutor::reset() {
  law_.reset();
  status_ = ExecutionStatus{};
  have_joints_ = have_tau_ = started_ = false;
  good_rate_.setZero();
  bad_joints_since_ = open_since_ = stuck_since_ = -1.0;
  bad_pose_ = pose_new_ = have_jump_ = false;
  pose_error_.setZero();
  pose_rate_.setZero();
  have_error_ = false;
}

void PlanExecutor::addPartPose(double stamp, const Pose& pose) {
  if (!std::isfinite(stamp) || !std::isfinite(pose.x) || !std::isfinite(pose.y) ||
      !std::isfinite(pose.phi)) {
    bad_pose_ = true;
    ++status_.bad_readings;
    return;
  }
  if (schedule_.partFeedback()) law_.addPartPose(stamp, pose);
  if (!pose_new_ || stamp >= pose_stamp_) {
    pose_stamp_ = stamp;
    pose_ = pose;
  }
  pose_new_ = true;
}

void PlanExecutor::hold(HoldReason why) {
  if (law_.holding() || !started_) return;
  law_.hold();
  status_.hold_reason = why;
  status_.hold_time = last_t_;
  status_.verdict = ExecutionVerdict::kHolding;
}

bool PlanExecutor::plausible(double t, const VecU& joints) {
  // The prediction: the last good reading moved on at the rate of the last two good ones.
  const double dt = t - good_t_, grow = std::max(1.0, (dt * dt) / (h_ * h_));
  bool near_good = true, near_jump = have_jump_;
  for (int j = 0; j < joints.size(); ++j) {
    const double gate = gate_[j] * grow;
    near_good = near_good && std::abs(joints[j] - (good_joints_[j] + dt * good_rate_[j])) <= gate;
    // A second jump from the first, as far as the joint moved per period before.
    near_jump = near_jump && std::abs(joints[j] - jump_[j]) <=
                                 gate_[j] + std::abs(good_rate_[j]) * (t - jump_t_);
  }
  if (near_good) {
    have_jump_ = false;
    return true;
  }
  // Two readings in a row that agree with each other: the joints did move (an impact), and
  // the second is taken.
  jump_ = joints;
  jump_t_ = t;
  have_jump_ = !near_jump;
  return near_jump;
}

void PlanExecutor::step(double t, const VecU& joints, VecU& tau) {
  status_.flags = 0;
  if (!std::isfinite(t)) {
    ++status_.bad_readings;
    status_.flags |= kFlagBadTime;
    if (!have_tau_) schedule_.reference(schedule_.planStart(), at_stamp_);
    tau = have_tau_ ? good_tau_ : at_stamp_.tau;
    return;
  }
  if (started_ && t < last_t_ - 0.5 * h_) reset();  // time went back: a new run
  if (started_ && t > last_t_ + 1.5 * h_) status_.flags |= kFlagLateTick;
  const bool finite_joints = joints.size() == good_joints_.size() && joints.allFinite();
  if (finite_joints && started_ && !plausible(t, joints)) {
    // A jump no actuator can make in one period: a spike, bridged like a bad reading.
    ++status_.bad_readings;
    status_.flags |= kFlagBadJoints | kFlagJointJump;
  } else if (finite_joints) {
    if (have_joints_ && t > good_t_) good_rate_ = (joints - good_joints_) / (t - good_t_);
    good_t_ = t;
    good_joints_ = joints;
    have_joints_ = true;
    bad_joints_since_ = -1.0;
  } else {
    ++status_.bad_readings;
    status_.flags |= kFlagBadJoints;
    if (bad_joints_since_ < 0.0) bad_joints_since_ = t;
  }
  if (!have_joints_) {
    // Nothing measured yet: the plan's own input at t, the law not started.
    schedule_.reference(t, at_stamp_);
    tau = at_stamp_.tau;
    status_.plan_time = t;
    status_.verdict = ExecutionVerdict::kDegraded;
    return;
  }
  const bool clamped = law_.compute(t, good_joints_, tau);
  started_ = true;
  last_t_ = t;
  if (!tau.allFinite()) {
    tau = have_tau_ ? good_tau_ : law_.reference().tau;
    hold(HoldReason::kBadOutput);
  } else {
    good_tau_ = tau;
    have_tau_ = true;
  }
  measure(t, good_joints_, clamped);
  judge(t);
}

void PlanExecutor::measure(double t, const VecU& joints, bool clamped) {
  ExecutionStatus& s = status_;
  s.plan_time = t;
  const ReferenceSample& ref = law_.reference();
  const VecQ& q = law_.controlState();
  double dp = std::hypot(q[layout::kX] - ref.q[layout::kX], q[layout::kY] - ref.q[layout::kY]);
  double da = std::abs(std::remainder(q[layout::kPhi] - ref.q[layout::kPhi], 2.0 * M_PI));
  if (pose_new_) {
    // The newest pose against the reference at its stamp, and the error's rate from the
    // pose before it (smoothed): the error is carried to the present over the pose's age,
    // as the law's estimator carries a late pose.
    schedule_.reference(law_.planTime(pose_stamp_), at_stamp_);
    const Eigen::Vector3d e(pose_.x - at_stamp_.q[layout::kX], pose_.y - at_stamp_.q[layout::kY],
                            std::remainder(pose_.phi - at_stamp_.q[layout::kPhi], 2.0 * M_PI));
    const double dt = pose_stamp_ - error_stamp_;
    if (have_error_ && dt > 0.0) pose_rate_ = 0.5 * pose_rate_ + 0.5 * (e - pose_error_) / dt;
    pose_error_ = e;
    error_stamp_ = pose_stamp_;
    have_error_ = true;
    s.pose_seen = true;
    pose_new_ = false;
  }
  if (s.pose_seen) {
    s.pose_age = t - pose_stamp_;
    const double carry = std::min(s.pose_age, limits_.stale_pose_time);
    const Eigen::Vector3d e = pose_error_ + carry * pose_rate_;
    dp = std::max(dp, std::hypot(e[0], e[1]));
    da = std::max(da, std::abs(e[2]));
    if (s.pose_age > limits_.stale_pose_time) s.flags |= kFlagStalePose;
  }
  if (bad_pose_) s.flags |= kFlagBadPose;
  bad_pose_ = false;
  s.position_deviation = dp;
  s.angle_deviation = da * 180.0 / M_PI;

  const ContactTick& tick = law_.contacts();
  const int m = schedule_.model().numFingers();
  s.planned = tick.roles;
  s.estimated = tick.estimated;
  s.contact_open = s.slider_stuck = s.tip_slipping = 0;
  s.stroke_deviation = s.stroke_speed_deviation = 0.0;
  const VecQ& v = law_.controlVelocity();
  for (int i = 0; i < m; ++i) {
    const ContactRole r = tick.roles[i];
    if (!relied(r)) continue;
    const std::uint32_t bit = 1u << i;
    const int k = layout::stroke(i);
    s.stroke_deviation =
        std::max(s.stroke_deviation, std::abs(joints[layout::fingerForce(i)] - ref.q[k]));
    if (r == ContactRole::kStick)
      s.stroke_speed_deviation = std::max(s.stroke_speed_deviation, std::abs(v[k] - ref.v[k]));
    if (tick.estimated[i] == ContactMode::kSeparated) s.contact_open |= bit;
    if (r == ContactRole::kStick && tick.estimated[i] == ContactMode::kSlide) s.tip_slipping |= bit;
    if (slipSign(r) != 0 && !tick.loose[i]) s.slider_stuck |= bit;
  }
  s.saturated = clamped;
  if (clamped) s.flags |= kFlagSaturated;
  if (s.tip_slipping != 0) s.flags |= kFlagTipSlipping;
  if (s.contact_open != 0) s.flags |= kFlagContactOpen;
  open_since_ = s.contact_open == 0 ? -1.0 : (open_since_ < 0.0 ? t : open_since_);
  stuck_since_ = s.slider_stuck == 0 ? -1.0 : (stuck_since_ < 0.0 ? t : stuck_since_);
  if (stuck_since_ >= 0.0 && t - stuck_since_ >= limits_.slider_stuck_time)
    s.flags |= kFlagSliderStuck;
  if (dp > limits_.degraded_position || da > limits_.degraded_angle) s.flags |= kFlagDeviation;
  if (s.stroke_deviation > limits_.degraded_stroke ||
      s.stroke_speed_deviation > limits_.degraded_stroke_speed)
    s.flags |= kFlagStrokeError;
  if (dp > limits_.leaving_position || da > limits_.leaving_angle ||
      s.stroke_deviation > limits_.leaving_stroke ||
      s.stroke_speed_deviation > limits_.leaving_stroke_speed)
    s.flags |= kFlagOffTube;
}

void PlanExecutor::judge(double t) {
  ExecutionStatus& s = status_;
  const bool leaving = (s.flags & kFlagOffTube) != 0 ||
                       (open_since_ >= 0.0 && t - open_since_ >= limits_.contact_open_time);
  if (!law_.holding() && limits_.hold_on_faults) {
    if (bad_joints_since_ >= 0.0 && t - bad_joints_since_ >= limits_.bad_joint_time)
      hold(HoldReason::kBadJoints);
    else if (schedule_.partFeedback() && s.pose_seen && s.pose_age > limits_.stale_pose_hold)
      hold(HoldReason::kStalePose);
  }
  if (!law_.holding() && leaving && limits_.hold_on_leaving) {
    hold(HoldReason::kLeaving);
    s.verdict = ExecutionVerdict::kLeaving;  // this tick's; held from the next on
    return;
  }
  if (law_.holding()) {
    s.verdict = ExecutionVerdict::kHolding;
    return;
  }
  const std::uint32_t degrading =
      kFlagDeviation | kFlagSaturated | kFlagStalePose | kFlagBadJoints | kFlagBadPose |
      kFlagTipSlipping | kFlagSliderStuck | kFlagStrokeError | kFlagContactOpen | kFlagLateTick;
  if (leaving)
    s.verdict = ExecutionVerdict::kLeaving;
  else if ((s.flags & degrading) != 0)
    s.verdict = ExecutionVerdict::kDegraded;
  else if (t >= schedule_.planEnd())
    s.verdict = ExecutionVerdict::kDone;
  else
    s.verdict = ExecutionVerdict::kOnPlan;
}

}  // namespace rbsf
