#include "rbsf/dynamics/control/control_law.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

namespace {

/// Part samples that may wait for the next compute(): a sensor faster than the loop
/// delivers a few per period at most.
constexpr int kPendingCapacity = 16;
/// The joint-only alpha-beta filter's largest tracking index (acceleration noise x h^2 /
/// measurement noise): alpha 0.979, beta 1.46, well inside the stable region.
constexpr double kMaxTrackingIndex = 10.0;

}  // namespace

ControlLaw::ControlLaw(const FeedbackSchedule& schedule)
    : schedule_(schedule),
      ws_(std::make_unique<SimulatorWorkspace>(schedule.model().numFingers())),
      qp_(schedule.model(), schedule.settings().forces),
      state_(VecQ::Zero(schedule.model().configDim()), VecQ::Zero(schedule.model().configDim())) {
  const double h = schedule.timeStep();
  const PartPoseSensing& camera = schedule.sensing().part_pose;
  const double history_time = camera.present ? camera.latency + 2.0 / camera.rate : 0.0;
  const int n = schedule.model().configDim(), nu = schedule.model().controlDim();
  ring_.resize(static_cast<std::size_t>(std::ceil(history_time / h)) + 2);
  pending_.resize(kPendingCapacity);
  applied_ = VecU::Zero(nu);
  demand_ = VecU::Zero(nu);
  e_ = VecX::Zero(2 * n);
  d_ = VecX::Zero(2 * n);
  ej_ = dej_ = alpha_ = beta_ = VecU::Zero(nu);
  for (int j = 0; j < nu; ++j) {
    const double noise = std::max(j == layout::kTauTheta ? schedule.sensing().joints.angle_noise
                                                         : schedule.sensing().joints.stroke_noise,
                                  1e-12);
    // The tracking index, capped: noise-free encoders would give the filter's limit
    // alpha = 1, beta = 2, which is marginally stable and rings.
    const double lambda =
        std::min(schedule.settings().servo.servo_acceleration * h * h / noise, kMaxTrackingIndex);
    const double r = (4.0 + lambda - std::sqrt(8.0 * lambda + lambda * lambda)) / 4.0;
    alpha_[j] = 1.0 - r * r;
    beta_[j] = 2.0 * (2.0 - alpha_[j]) - 4.0 * std::sqrt(1.0 - alpha_[j]);
  }
  at_.q = VecQ::Zero(n);
  at_.v = VecQ::Zero(n);
  tick_.slip_floor = VecC::Zero(schedule.model().numFingers());
  at_.tau = VecU::Zero(nu);
  mid_ = at_;
}

void ControlLaw::reset() {
  step_ = -1;
  start_set_ = false;
  tick_.loose.fill(false);
  pulled_.fill(0.0);
  stroke_offset_.fill(0.0);
  reach_.fill(0.0);
  joining_ = 0;
  num_pending_ = 0;
  dropped_ = 0;
  demand_.setZero();
  applied_.setZero();
  xi_.setZero();
  holding_ = false;
  // The estimate's state (its closest-point hints and contact memory among it) starts as at
  // construction, since the joint-only law never rebuilds it: a restart repeats the first run
  // bit for bit.
  const int n = schedule_.model().configDim();
  state_ = SimState(VecQ::Zero(n), VecQ::Zero(n));
  qp_.reset();
}

void ControlLaw::hold() {
  if (step_ < 0 || holding_) return;
  hold_start_ = entry(step_).t;
  holding_ = true;
}

double ControlLaw::planTime(double t, double* rate) const {
  if (!holding_ || t <= hold_start_) {
    if (rate != nullptr) *rate = 1.0;
    return t;
  }
  // s' falls linearly from 1 to 0 over hold_stop, then stays 0.
  const double T = schedule_.settings().timing.hold_stop;
  const double d = std::min(t - hold_start_, T);
  if (rate != nullptr) *rate = T > 0.0 ? 1.0 - d / T : 0.0;
  return hold_start_ + (T > 0.0 ? d - 0.5 * d * d / T : 0.0);
}

void ControlLaw::sampleReference(double t, ReferenceSample& out) const {
  double rate = 1.0;
  schedule_.reference(planTime(t, &rate), out);
  if (rate != 1.0) out.v *= rate;
}

void ControlLaw::addPartPose(double stamp, const Pose& pose) {
  if (!schedule_.partFeedback() || num_pending_ >= kPendingCapacity || !std::isfinite(stamp) ||
      !std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.phi)) {
    ++dropped_;
    return;
  }
  pending_[num_pending_++] = {stamp, pose};
}

void ControlLaw::jointUpdate(int knot, const VecU& joints) {
  const int n = schedule_.model().configDim();
  VecU r = joints;
  for (int j = 0; j < r.size(); ++j) r[j] -= state_.q[layout::inputToConfig(j)];
  d_.noalias() = schedule_.jointGain(knot) * r;
  state_.q += d_.head(n);
  state_.v += d_.tail(n);
}

void ControlLaw::applyPartSample(const PartSample& s) {
  const double h = schedule_.timeStep();
  const int n = schedule_.model().configDim();
  const long back = std::max(0L, std::lround((entry(step_).t - s.stamp) / h));
  if (back > step_ || back + 1 >= static_cast<long>(ring_.size())) {
    ++dropped_;
    return;
  }
  const long i = step_ - back;
  Entry& at = entry(i);
  const Eigen::Vector3d r(s.pose.x - at.pose[0], s.pose.y - at.pose[1],
                          std::remainder(s.pose.phi - at.pose[2], 2.0 * M_PI));
  d_.noalias() = schedule_.partGain(at.knot) * r;
  at.pose += Eigen::Vector3d(d_[layout::kX], d_[layout::kY], d_[layout::kPhi]);
  for (long j = i + 1; j <= step_; ++j) {
    // Carry the correction one step, then take off what the joint update of that step
    // would have removed had it seen the corrected estimate.
    Entry& next = entry(j);
    e_.noalias() = schedule_.Ad(entry(j - 1).knot) * d_;
    const Eigen::MatrixXd& L = schedule_.jointGain(next.knot);
    VecU hd(L.cols());
    for (int c = 0; c < hd.size(); ++c) hd[c] = e_[layout::inputToConfig(c)];
    d_.noalias() = e_ - L * hd;
    next.pose += Eigen::Vector3d(d_[layout::kX], d_[layout::kY], d_[layout::kPhi]);
  }
  state_.q += d_.head(n);
  state_.v += d_.tail(n);
  // Sticking contacts re-anchor where the corrected estimate puts them: the simulator's
  // drift correction would otherwise pull the part back to the old anchor.
  closeGaps(state_.q, state_.mode);
  state_.anchored.fill(false);
  keepContactVelocities();
}

void ControlLaw::keepContactVelocities() {
  const RbsfModel& model = schedule_.model();
  const int m = model.numFingers();
  ModelData& data = ws_->data;
  data.xi_hint = state_.xi_hint;
  model.updateContacts(state_.q, data);
  MatQR W(model.configDim(), 0);
  for (int i = 0; i < m; ++i) {
    if (state_.mode[i] == ContactMode::kSeparated) continue;
    W.conservativeResize(Eigen::NoChange, W.cols() + 1);
    W.col(W.cols() - 1) = data.G1.col(i);
    if (state_.mode[i] != ContactMode::kStick) continue;
    W.conservativeResize(Eigen::NoChange, W.cols() + 1);
    W.col(W.cols() - 1) = data.T.col(i);
  }
  if (W.cols() == 0) return;
  MatQR MinvW = W;
  model.applyMassInverse(state_.q, MinvW);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows> D =
      W.transpose() * MinvW;
  D.diagonal().array() += 1e-9 * D.diagonal().maxCoeff();
  const VecR lambda = D.ldlt().solve(-(W.transpose() * state_.v));
  state_.v.noalias() += MinvW * lambda;
}

void ControlLaw::closeGaps(VecQ& q, const ContactModes& modes) {
  // Gauss-Newton on the gaps of the touching contacts: the least part motion that closes
  // them (G1's part rows), twice.
  const RbsfModel& model = schedule_.model();
  const int m = model.numFingers();
  ModelData& data = ws_->data;
  data.xi_hint = state_.xi_hint;  // NaN before the first step: a global search
  for (int iteration = 0; iteration < 2; ++iteration) {
    model.updateContacts(q, data);
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxFingers> G(3, 0);
    VecC gap(0);
    for (int i = 0; i < m; ++i) {
      if (modes[i] == ContactMode::kSeparated) continue;
      G.conservativeResize(3, G.cols() + 1);
      gap.conservativeResize(gap.size() + 1);
      G.col(G.cols() - 1) = data.G1.col(i).head<3>();
      gap[gap.size() - 1] = data.contacts[i].gap;
    }
    if (G.cols() == 0) return;
    // Damped: where the contacts leave a motion free to first order (normals through one
    // point: a rotation about it), no correction is asked of it.
    MatCC D = G.transpose() * G;
    D.diagonal().array() += 1e-6 * D.diagonal().maxCoeff();
    const VecC w = D.ldlt().solve(gap);
    q.head<3>() -= G * w;
  }
  state_.xi_hint = data.xi_hint;  // the next search starts here
}

bool ControlLaw::computeJointOnly(double t, const VecU& joints, VecU& tau) {
  const double h = schedule_.timeStep();
  const int n = schedule_.model().configDim(), nu = schedule_.model().controlDim();
  sampleReference(t, at_);
  if (step_ >= 0) {
    const long advance = std::max(1L, std::lround((t - entry(step_).t) / h));
    ej_ += static_cast<double>(advance) * h * dej_;
    step_ += advance;
  } else {
    step_ = 0;
    for (int j = 0; j < nu; ++j) ej_[j] = joints[j] - at_.q[layout::inputToConfig(j)];
    dej_ = -at_.v.segment(layout::kTheta, nu);  // the cell starts at rest
  }
  entry(step_).t = t;
  entry(step_).knot = knotAt(t);
  e_.setZero(2 * n);
  for (int j = 0; j < nu; ++j) {
    const int k = layout::inputToConfig(j);
    const double r = joints[j] - at_.q[k] - ej_[j];
    ej_[j] += alpha_[j] * r;
    dej_[j] += beta_[j] / h * r;
    e_[k] = ej_[j];
    e_[n + k] = dej_[j];
  }
  state_.q = at_.q + e_.head(n);
  state_.v = at_.v + e_.tail(n);
  num_pending_ = 0;
  // The part: where the strokes put it. At the start the contacts the plan starts on touch
  // (the cell places those fingers under the part), which fixes its pose; later it rides on
  // the planned contacts with that offset from the plan's pose (in the part's frame). A
  // finger the plan starts lifted tells nothing of the part.
  q_est_ = state_.q;
  v_est_ = state_.v;
  if (!start_set_) {
    closeGaps(q_est_, schedule_.modes(0));
    const Vec2 d = rotate(-at_.q[layout::kPhi], Vec2(q_est_[layout::kX] - at_.q[layout::kX],
                                                     q_est_[layout::kY] - at_.q[layout::kY]));
    part_offset_ = Eigen::Vector3d(d.x(), d.y(), q_est_[layout::kPhi] - at_.q[layout::kPhi]);
  } else {
    const Vec2 d = rotate(at_.q[layout::kPhi], Vec2(part_offset_[0], part_offset_[1]));
    q_est_[layout::kX] += d.x();
    q_est_[layout::kY] += d.y();
    q_est_[layout::kPhi] += part_offset_[2];
    closeGaps(q_est_, schedule_.modes(entry(step_).knot));
    const Vec2 o = rotate(-at_.q[layout::kPhi], Vec2(q_est_[layout::kX] - at_.q[layout::kX],
                                                     q_est_[layout::kY] - at_.q[layout::kY]));
    part_offset_ = Eigen::Vector3d(o.x(), o.y(), q_est_[layout::kPhi] - at_.q[layout::kPhi]);
  }
  blendStart(t, e_);
  const bool clamped = control(t, entry(step_).knot, e_, Eigen::Vector3d::Zero(), tau);
  applied_ = tau;
  return clamped;
}

bool ControlLaw::compute(double t, const VecU& joints, VecU& tau) {
  const double h = schedule_.timeStep();
  const int n = schedule_.model().configDim();
  if (!schedule_.partFeedback()) {
    if (step_ >= 0 && t < entry(step_).t - 0.5 * h) reset();
    return computeJointOnly(t, joints, tau);
  }
  if (step_ >= 0 && t < entry(step_).t - 0.5 * h) reset();  // time went back: a new run
  if (step_ < 0) {
    // Start at rest: the part where the plan starts it, the joints where they are measured
    // (an estimate started elsewhere would read the first joint residual as a velocity).
    schedule_.reference(t, at_);
    VecQ q = at_.q;
    for (int j = 0; j < joints.size(); ++j) q[layout::inputToConfig(j)] = joints[j];
    closeGaps(q, schedule_.modes(0));
    state_ = SimState(q, VecQ::Zero(n));
    state_.t = t;
    step_ = 0;
  } else {
    const long advance = std::max(1L, std::lround((t - entry(step_).t) / h));
    for (long a = 0; a < advance; ++a) {
      schedule_.estimatorSimulator().step(state_, applied_, *ws_, nullptr,
                                          &schedule_.estimatorSlipTolerance(entry(step_).knot));
      Entry& next = entry(++step_);
      next.t = entry(step_ - 1).t + h;
      next.knot = knotAt(next.t);
      next.pose =
          Eigen::Vector3d(state_.q[layout::kX], state_.q[layout::kY], state_.q[layout::kPhi]);
    }
  }
  Entry& cur = entry(step_);
  cur.t = t;
  cur.knot = knotAt(t);
  jointUpdate(cur.knot, joints);
  cur.pose = Eigen::Vector3d(state_.q[layout::kX], state_.q[layout::kY], state_.q[layout::kPhi]);
  for (int p = 0; p < num_pending_; ++p) applyPartSample(pending_[p]);
  num_pending_ = 0;

  sampleReference(t, at_);
  e_.head(n) = state_.q - at_.q;
  e_.tail(n) = state_.v - at_.v;
  q_est_ = state_.q;
  v_est_ = state_.v;
  blendStart(t, e_);
  const bool clamped = control(t, cur.knot, e_, xi_, tau);
  applied_ = tau;
  if (!clamped) {
    const FeedbackSettings& fs = schedule_.settings();
    for (int c = 0; c < layout::kObjectDim; ++c) {
      const double bound = fs.lqr.integral_limit * fs.lqr.integral_time *
                           (c == layout::kPhi ? fs.lqr.angle : fs.lqr.position);
      xi_[c] = std::clamp(xi_[c] + h * e_[c], -bound, bound);
    }
  }
  return clamped;
}

bool ControlLaw::computeFromState(double t, const VecQ& q, const VecQ& v, VecU& tau) {
  const int n = schedule_.model().configDim();
  schedule_.reference(t, at_);
  VecX e(2 * n);
  e.head(n) = q - at_.q;
  e.tail(n) = v - at_.v;
  q_est_ = q;
  v_est_ = v;
  exact_state_ = true;
  const bool clamped = control(t, schedule_.knotAt(t), e, Eigen::Vector3d::Zero(), tau);
  exact_state_ = false;
  return clamped;
}

void ControlLaw::blendStart(double t, VecX& e) {
  const int n = schedule_.model().configDim();
  if (!start_set_) {
    start_error_ = e;
    start_error_.tail(n).setZero();
    start_time_ = t;
    start_set_ = true;
  }
  const double T = schedule_.settings().timing.start_blend;
  if (T > 0.0) e.noalias() -= std::exp(-(t - start_time_) / T) * start_error_;
}

bool ControlLaw::control(double t, int knot, const VecX& e, const Eigen::Vector3d& xi, VecU& tau) {
  const int nu = schedule_.model().controlDim(), m = schedule_.model().numFingers();
  sampleReference(t + 0.5 * schedule_.timeStep(), mid_);
  demand_ = mid_.tau;
  demand_.noalias() -= schedule_.gain(knot) * e;
  demand_.noalias() -= schedule_.integralGain(knot) * xi;
  joinDemand(t, knot, e);
  // The tick's contacts: the plan's roles; touching where the estimate's gap is closed
  // (within what the strokes' noise can tell), sliding where the estimator's contact memory
  // slides them or, on an exact state, where they slip.
  ContactTick& tick = tick_;
  tick.roles = schedule_.roles(knot);
  qp_.data().xi_hint = state_.xi_hint;
  const ModelData& data = qp_.updateContacts(q_est_);
  const bool exact = exact_state_;
  const FeedbackSettings& fs = schedule_.settings();
  const double touch = 10.0 * schedule_.sensing().joints.stroke_noise + 1e-5;
  tick.estimated.fill(ContactMode::kSeparated);
  // A joining finger is a force the law sets, not a contact its forces are shared through:
  // where it touches is not known, and the QP would move the others' load onto it.
  const std::uint32_t joining = schedule_.joining(knot);
  // On an exact state a contact the plan keeps stuck slides only above exact_slip_speed (a
  // step's own drift is not a slip), the others above the plant's tolerance, as the estimator
  // reads them.
  const double tolerance = 10.0 * schedule_.simulator().settings().slip_tolerance;
  for (int i = 0; i < m; ++i) {
    if (data.contacts[i].gap > touch || ((joining >> i) & 1u)) continue;
    const double drift =
        tick.roles[i] == ContactRole::kStick ? fs.contacts.exact_slip_speed : tolerance;
    const bool slides = exact ? std::abs(data.T.col(i).dot(v_est_)) > drift
                              : schedule_.partFeedback() && state_.mode[i] == ContactMode::kSlide;
    tick.estimated[i] = slides ? ContactMode::kSlide : ContactMode::kStick;
  }
  // Planned sliders break loose once: seen slipping their way (the estimate or the exact
  // state), or, without the part's pose, after the law has pulled them for breakaway_time.
  // A loose slider keeps at least the slip floor, or the reference's own slip where slower.
  const double dt = schedule_.timeStep();
  const double floor = qp_.settings().slip_speed;
  for (int i = 0; i < m; ++i) {
    const int sgn = slipSign(tick.roles[i]);
    tick.slip_floor[i] = 0.0;
    if (sgn == 0 || tick.estimated[i] == ContactMode::kSeparated) {
      tick.loose[i] = false;
      pulled_[i] = 0.0;
      continue;
    }
    // A slider seen stuck again (stopped by a transient) is pulled loose again.
    const double slip = sgn * data.T.col(i).dot(v_est_);
    // On an exact state the simulator's own tolerance tells; an estimate needs a slip it can
    // tell from its noise.
    const bool sees = exact || schedule_.partFeedback();
    const double seen = exact ? tolerance : fs.contacts.estimator_slip_speed;
    // Slipping either way: the prediction takes its kinetic friction against the slip.
    const bool slipping =
        sees && (std::abs(slip) > seen || (!exact && state_.mode[i] == ContactMode::kSlide));
    const double planned = sgn * data.T.col(i).dot(at_.v);
    // Where the reference slows the slider to rest (its slip under the floor and falling),
    // the run is ending: seen stuck there, it is where the plan brings it, and a pull would
    // start the slide again. It is a contact at rest not relied on, as in the rest after the
    // run. (Unseen, it stays a slider: its prediction takes kinetic friction until the run
    // ends.)
    if (sees && !slipping && planned < floor && sgn * data.T.col(i).dot(mid_.v) < planned) {
      tick.roles[i] = ContactRole::kFree;
      tick.loose[i] = false;
      pulled_[i] = 0.0;
      continue;
    }
    if (sees) {
      // Stuck again: an exact state shows it; an estimate, where the reference slides the tip
      // faster than the estimate can tell and the estimate sees a fraction of that slip.
      const bool stuck =
          exact ? std::abs(slip) < 0.1 * seen : planned > seen && std::abs(slip) < 0.25 * planned;
      tick.loose[i] = slipping || (tick.loose[i] && !stuck);
    } else {
      // Without the part's pose the slip cannot be seen: loose once pulled long enough.
      tick.loose[i] = tick.loose[i] || pulled_[i] >= fs.contacts.breakaway_time;
    }
    if (!tick.loose[i]) pulled_[i] += dt;
    // The floor holds where the reference itself slides this way at least that fast.
    tick.slip_floor[i] = planned >= floor ? floor : 0.0;
  }
  qp_.solve(q_est_, v_est_, tick, demand_, tau);

  const Cell& c = schedule_.model().cell();
  bool clamped = false;
  for (int j = 0; j < nu; ++j) {
    const double limit = c.inputLimit(j);
    clamped = clamped || std::abs(tau[j]) >= limit * (1.0 - 1e-9) || std::abs(demand_[j]) > limit;
  }
  return clamped;
}

void ControlLaw::joinDemand(double t, int knot, const VecX& e) {
  const ContactReading& cr = schedule_.settings().contacts;
  const Eigen::MatrixXd& K = schedule_.gain(knot);
  const Cell& cell = schedule_.model().cell();
  const std::uint32_t joining = schedule_.joining(knot);
  const double dt = std::max(t - last_control_t_, 0.0);
  const double fade = std::exp(-dt / cr.join_settle);
  last_control_t_ = t;
  for (int i = 0; i < schedule_.model().numFingers(); ++i) {
    const int j = layout::fingerForce(i), k = layout::stroke(i);
    if ((joining >> i) & 1u) {
      // Servoed join_reach past the planned stroke, the push capped: the finger rises until
      // it meets the part wherever the part is, and then presses it lightly.
      stroke_offset_[i] = 0.0;
      if (std::abs(mid_.v[k]) < 0.1 * cr.join_speed)
        reach_[i] = std::min(reach_[i] + cr.join_speed * dt, cr.join_reach);
      demand_[j] = std::min(demand_[j] + K(j, k) * reach_[i],
                            mid_.tau[j] + cr.join_press * cell.object.mass * cell.gravity);
      continue;
    }
    reach_[i] = 0.0;
    const ContactRole r = schedule_.roles(knot)[i];
    const bool relied = r == ContactRole::kStick || slipSign(r) != 0;
    if ((joining_ >> i) & 1u)
      stroke_offset_[i] = relied ? e[k] : 0.0;  // joined where it met the part
    else
      stroke_offset_[i] *= fade;
    if (stroke_offset_[i] != 0.0) demand_.noalias() += K.col(k) * stroke_offset_[i];
  }
  joining_ = joining;
}

void ControlLaw::recordApplied(const VecU& tau) { applied_ = tau; }

void ControlLaw::estimate(VecQ& q, VecQ& v) const {
  if (step_ < 0) {
    ReferenceSample r;
    schedule_.reference(schedule_.planStart(), r);
    q = r.q;
    v = VecQ::Zero(r.q.size());
    return;
  }
  q = state_.q;
  v = state_.v;
}

}  // namespace rbsf
