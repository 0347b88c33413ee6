#include "rbsf/dynamics/control/feedback_schedule.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Diagonal of per-coordinate values over (q, v) in state_layout.h order.
VectorXd stateDiagonal(int m, double pos, double ang, double base, double stroke, double dpos,
                       double dang, double dbase, double dstroke) {
  const int n = layout::configDim(m);
  VectorXd d(2 * n);
  for (int half = 0; half < 2; ++half) {
    const int o = half * n;
    d[o + layout::kX] = d[o + layout::kY] = half ? dpos : pos;
    d[o + layout::kPhi] = half ? dang : ang;
    d[o + layout::kTheta] = half ? dbase : base;
    for (int i = 0; i < m; ++i) d[o + layout::stroke(i)] = half ? dstroke : stroke;
  }
  return d;
}

void symmetrize(MatrixXd& S) { S = 0.5 * (S + S.transpose()).eval(); }

/// \brief The estimator's simulator settings (FeedbackSchedule::estimatorSimulator()).
SimulatorSettings estimatorSettings(const RbsfModel& model, const SimulatorSettings& simulator,
                                    const Sensing& sensing, const FeedbackSettings& settings) {
  SimulatorSettings e = simulator;
  // Without friction there is no stick to lose, and a slow slide must stay a slide.
  if (model.cell().friction.mu_static > 0.0)
    e.slip_tolerance = std::max(e.slip_tolerance, settings.contacts.estimator_slip_speed);
  e.contact_tolerance = std::max(e.contact_tolerance, 10.0 * sensing.joints.stroke_noise);
  e.activation_distance = std::max(e.activation_distance, 2.0 * e.contact_tolerance);
  e.drift_moves_part_only = true;
  return e;
}

/// \brief Every weight, period and noise positive; the hold, the horizon's tail, the damping
///        and the integral action not negative. \throws InputError.
void checkSettings(const FeedbackSettings& s) {
  for (double x :
       {s.timing.gain_period, s.lqr.position, s.lqr.angle, s.lqr.base_angle, s.lqr.stroke,
        s.lqr.speed, s.lqr.angular_speed, s.lqr.base_rate, s.lqr.stroke_speed, s.lqr.input_fraction,
        s.servo.natural_frequency, s.noise.part_acceleration, s.noise.part_angular_acceleration,
        s.noise.joint_acceleration, s.servo.servo_acceleration, s.noise.drift_speed,
        s.contacts.touch_gap})
    if (!(std::isfinite(x) && x > 0.0))
      throw InputError("feedback settings: every weight, period and noise must be positive");
  if (!(s.timing.settle_time >= 0.0 && s.timing.horizon_tail >= 0.0 &&
        s.servo.damping_ratio >= 0.0 && s.lqr.integral_time >= 0.0 && s.lqr.integral_limit >= 0.0))
    throw InputError(
        "feedback settings: settle_time, horizon_tail, damping_ratio, integral_time and "
        "integral_limit must be >= 0");
  if (!(s.contacts.join_reach >= 0.0 && s.contacts.join_press >= 0.0 &&
        s.contacts.join_speed > 0.0 && s.contacts.join_settle > 0.0))
    throw InputError(
        "feedback settings: join_reach and join_press must be >= 0, join_speed and "
        "join_settle > 0");
}

}  // namespace

FeedbackSchedule::FeedbackSchedule(const RbsfModel& model, ReferenceTrajectory trajectory,
                                   const Sensing& sensing, const SimulatorSettings& simulator,
                                   const FeedbackSettings& settings)
    : model_(model),
      simulator_(model, simulator),
      estimator_(model, estimatorSettings(model, simulator, sensing, settings)),
      reference_(std::move(trajectory)),
      sensing_(sensing),
      h_(simulator.time_step),
      settings_(settings) {
  if (!reference_.ready()) throw InputError("feedback schedule: the reference is empty");
  if (!(std::isfinite(h_) && h_ > 0.0))
    throw InputError("feedback schedule: the control period must be positive");
  checkSettings(settings_);
  steps_per_knot_ = std::max(1, static_cast<int>(std::lround(settings_.timing.gain_period / h_)));
  t0_ = reference_.startTime();

  ReferenceSample end;
  reference_.sample(reference_.endTime(), end);
  hold_q_ = end.q;
  hold_tau_ = end.tau;

  const double knot_span = steps_per_knot_ * h_;
  const int knots = 1 + static_cast<int>(std::ceil((holdEnd() - t0_) / knot_span - 1e-9));
  const ModeDynamics dynamics(model_);
  SimulatorWorkspace ws(model_.numFingers());
  std::vector<MatrixXd> tangent;
  ReferenceSample at, mid;
  for (int k = 0; k < knots; ++k) {
    const double t = t0_ + k * knot_span;
    reference(t, at);
    reference(t + 0.5 * h_, mid);
    ContactRoles roles;
    modes_.push_back(plannedModes(t, ws, roles));
    roles_.push_back(roles);
    // The raised slip threshold keeps a tip stuck through the estimate's noise; a tip the
    // plan lets slide or lift must slip as the plant's does, or the estimate keeps it stuck
    // while the real one slides and the two part poses separate.
    VecC slip(model_.numFingers());
    for (int i = 0; i < slip.size(); ++i)
      slip[i] = roles[i] == ContactRole::kStick || roles[i] == ContactRole::kUnplanned
                    ? estimator_.settings().slip_tolerance
                    : simulator_.settings().slip_tolerance;
    estimator_slip_.push_back(slip);
    ModeLinearization lin = dynamics.linearize(at.q, at.v, mid.tau, modes_.back());
    F_.push_back(lin.F);
    const MatrixXd A2 = lin.A * lin.A;
    Ad_.push_back(MatrixXd::Identity(lin.A.rows(), lin.A.cols()) + h_ * lin.A + 0.5 * h_ * h_ * A2);
    Bd_.push_back(h_ * lin.B + 0.5 * h_ * h_ * lin.A * lin.B);
    tangent.push_back(std::move(lin.tangent));
  }
  markJoining();
  if (partFeedback())
    computeLqr(tangent);
  else
    computePd();
  computeKalman();
}

void FeedbackSchedule::reference(double t, ReferenceSample& out) const {
  if (t <= reference_.endTime()) {
    reference_.sample(t, out);
    return;
  }
  reference_.sample(reference_.endTime(), out);
  out.t = t;
  out.q = hold_q_;
  out.v.setZero(hold_q_.size());
  out.tau = hold_tau_;
}

ContactModes FeedbackSchedule::plannedModes(double t, SimulatorWorkspace& ws,
                                            ContactRoles& roles) const {
  const int m = model_.numFingers();
  const SimulatorSettings& sim = simulator_.settings();
  ReferenceSample a, mid;
  reference(t, a);
  reference(t + 0.5 * h_, mid);
  // One simulator step from the reference, its contacts remembered as the reference moves
  // them (sliding where they slip, sticking otherwise): the modes the cell's physics takes
  // from x_ref(t) under the plan's input.
  SimState state(a.q, a.v);
  ModelData& data = ws.data;
  data.xi_hint.setConstant(std::numeric_limits<double>::quiet_NaN());
  model_.updateContacts(a.q, data);
  VecC slip = VecC::Zero(m);
  for (int i = 0; i < m; ++i) {
    slip[i] = data.T.col(i).dot(a.v);
    if (!(data.contacts[i].gap <= settings_.contacts.touch_gap)) continue;
    const bool slides = std::abs(slip[i]) > sim.slip_tolerance;
    state.mode[i] = slides ? ContactMode::kSlide : ContactMode::kStick;
    state.slip[i] = slip[i];
    state.friction_guess[i] = !slides         ? FrictionMode::kStick
                              : slip[i] > 0.0 ? FrictionMode::kSlidePositive
                                              : FrictionMode::kSlideNegative;
  }
  StepReport report;
  simulator_.step(state, mid.tau, ws, &report);
  // The roles: the plan's own, else what that step did (a contact it presses sticks or
  // slides the way the reference slips it).
  const double min_force =
      settings_.contacts.min_normal_force * model_.cell().object.mass * model_.cell().gravity;
  roles = a.roles;
  if (!planned(roles)) {
    roles.fill(ContactRole::kUnplanned);
    for (int i = 0; i < m; ++i) roles[i] = roleOf(report.contacts[i], min_force);
  }
  // The LQR's mode: a contact the reference loads too lightly to rely on is no constraint of
  // it (a gain that pulled on it would open it), and one without friction slides whatever
  // its slip (the simulator labels a contact at rest as sticking).
  const bool friction = model_.cell().friction.mu_static > 0.0;
  ContactModes modes;
  modes.fill(ContactMode::kSeparated);
  for (int i = 0; i < m; ++i) {
    ContactMode mode = slipSign(roles[i]) != 0           ? ContactMode::kSlide
                       : roles[i] == ContactRole::kStick ? ContactMode::kStick
                                                         : ContactMode::kSeparated;
    if (!(report.contacts[i].f_n >= min_force)) mode = ContactMode::kSeparated;
    if (mode == ContactMode::kStick && !friction) mode = ContactMode::kSlide;
    modes[i] = mode;
  }
  return modes;
}

void FeedbackSchedule::markJoining() {
  joining_.assign(roles_.size(), 0u);
  for (int i = 0; i < model_.numFingers(); ++i) {
    bool from_lifted = false;  // the last role other than F was L
    for (std::size_t k = 0; k < roles_.size(); ++k) {
      const ContactRole r = roles_[k][i];
      if (r != ContactRole::kFree)
        from_lifted = r == ContactRole::kLifted;
      else if (from_lifted)
        joining_[k] |= 1u << i;
    }
  }
}

int FeedbackSchedule::knotAt(double t) const {
  const double k = std::floor((t - t0_) / (steps_per_knot_ * h_) + 1e-9);
  if (!(k > 0.0)) return 0;
  return static_cast<int>(std::min<double>(k, numKnots() - 1));
}

void FeedbackSchedule::computeLqr(const std::vector<MatrixXd>& tangent) {
  const FeedbackSettings& s = settings_;
  const int m = model_.numFingers(), nu = model_.controlDim();
  const VectorXd tol =
      stateDiagonal(m, s.lqr.position, s.lqr.angle, s.lqr.base_angle, s.lqr.stroke, s.lqr.speed,
                    s.lqr.angular_speed, s.lqr.base_rate, s.lqr.stroke_speed);
  const MatrixXd Q = tol.cwiseInverse().cwiseAbs2().asDiagonal();
  VectorXd rdiag(nu);
  rdiag[layout::kTauTheta] = model_.cell().base.torque_limit;
  for (int i = 0; i < m; ++i) rdiag[layout::fingerForce(i)] = model_.cell().fingers[i].force_limit;
  const MatrixXd R = (s.lqr.input_fraction * rdiag).cwiseInverse().cwiseAbs2().asDiagonal();

  const int knots = numKnots(), n = model_.configDim();
  // Integral of the part's pose error (x, y, phi): three states appended to z.
  const bool integral = s.lqr.integral_time > 0.0;
  const int ni = integral ? layout::kObjectDim : 0;
  VectorXd qi(ni);
  for (int c = 0; c < ni; ++c)
    qi[c] =
        1.0 / std::pow((c == layout::kPhi ? s.lqr.angle : s.lqr.position) * s.lqr.integral_time, 2);
  MatrixXd Hp = MatrixXd::Zero(ni, 2 * n);
  for (int c = 0; c < ni; ++c) Hp(c, c) = 1.0;
  K_.assign(knots, MatrixXd());
  Ki_.assign(knots, MatrixXd::Zero(nu, layout::kObjectDim));
  MatrixXd S;
  auto riccati = [&](const MatrixXd& Az, const MatrixXd& Bz, const MatrixXd& Qz, MatrixXd& K) {
    const MatrixXd SB = S * Bz;
    K = (R + Bz.transpose() * SB).ldlt().solve(SB.transpose() * Az);
    S = Qz + Az.transpose() * S * Az - Az.transpose() * SB * K;
    symmetrize(S);
  };
  for (int k = knots - 1; k >= 0; --k) {
    const MatrixXd& P = tangent[k];
    const int r = static_cast<int>(P.cols());
    MatrixXd Az = MatrixXd::Identity(r + ni, r + ni), Bz = MatrixXd::Zero(r + ni, nu);
    MatrixXd Qz = MatrixXd::Zero(r + ni, r + ni);
    Az.topLeftCorner(r, r) = P.transpose() * Ad_[k] * P;
    Az.bottomLeftCorner(ni, r) = h_ * Hp * P;
    Bz.topRows(r) = P.transpose() * Bd_[k];
    Qz.topLeftCorner(r, r) = P.transpose() * Q * P;
    Qz.bottomRightCorner(ni, ni) = qi.asDiagonal();
    MatrixXd K;
    if (k == knots - 1) {
      S = Qz;
      for (long j = std::lround(s.timing.horizon_tail / h_); j > 0; --j) riccati(Az, Bz, Qz, K);
    } else {
      // The manifold changes with the mode: carry the cost-to-go into this knot's basis.
      const int r1 = static_cast<int>(tangent[k + 1].cols());
      MatrixXd T = MatrixXd::Identity(r1 + ni, r + ni);
      T.topLeftCorner(r1, r) = tangent[k + 1].transpose() * P;
      S = T.transpose() * S * T;
    }
    for (int j = 0; j < steps_per_knot_; ++j) riccati(Az, Bz, Qz, K);
    K_[k] = K.leftCols(r) * P.transpose();
    if (integral) Ki_[k] = K.rightCols(ni);
  }
}

void FeedbackSchedule::computePd() {
  ReferenceSample start;
  reference_.sample(t0_, start);
  const VecQ& q_nominal = start.q;
  const Cell& c = model_.cell();
  const int m = model_.numFingers(), n = model_.configDim(), nu = model_.controlDim();
  MatQQ M;
  model_.massMatrix(q_nominal, M);
  VectorXd inertia(nu);
  const double r2 =
      q_nominal[layout::kX] * q_nominal[layout::kX] + q_nominal[layout::kY] * q_nominal[layout::kY];
  inertia[layout::kTauTheta] =
      M(layout::kTheta, layout::kTheta) + c.object.inertia + c.object.mass * r2;
  for (int i = 0; i < m; ++i)
    inertia[layout::fingerForce(i)] = c.fingers[i].mass + c.object.mass / m;
  const double w = settings_.servo.natural_frequency, z = settings_.servo.damping_ratio;
  MatrixXd K = MatrixXd::Zero(nu, 2 * n);
  for (int j = 0; j < nu; ++j) {
    const int k = layout::inputToConfig(j);
    K(j, k) = inertia[j] * w * w;
    K(j, n + k) = inertia[j] * 2.0 * z * w;
  }
  K_.assign(numKnots(), K);
  Ki_.assign(numKnots(), MatrixXd::Zero(nu, layout::kObjectDim));
}

void FeedbackSchedule::computeKalman() {
  const FeedbackSettings& s = settings_;
  const int n = model_.configDim(), nu = model_.controlDim();
  const int dim = 2 * n;
  const PartPoseSensing& pp = sensing_.part_pose;
  // Process noise per step: velocity white noise on positions (drift), and generalized-force
  // noise through the mode's constraints on velocities (F), sized as the accelerations it
  // would give each coordinate alone (M_kk x acceleration).
  const VectorXd drift = VectorXd::Constant(n, s.noise.drift_speed);
  MatQQ M;
  ReferenceSample start;
  reference_.sample(t0_, start);
  model_.massMatrix(start.q, M);
  VectorXd force(n);
  force[layout::kX] = force[layout::kY] = M(layout::kX, layout::kX) * s.noise.part_acceleration;
  force[layout::kPhi] = M(layout::kPhi, layout::kPhi) * s.noise.part_angular_acceleration;
  for (int j = layout::kTheta; j < n; ++j) force[j] = M(j, j) * s.noise.joint_acceleration;
  const MatrixXd Sf = force.cwiseAbs2().asDiagonal();
  // Joint measurements: q[kTheta..n-1].
  MatrixXd Hj = MatrixXd::Zero(nu, dim);
  VectorXd rj(nu);
  for (int j = 0; j < nu; ++j) {
    Hj(j, layout::inputToConfig(j)) = 1.0;
    const double sd =
        j == layout::kTauTheta ? sensing_.joints.angle_noise : sensing_.joints.stroke_noise;
    rj[j] = std::max(sd, 1e-9) * std::max(sd, 1e-9);
  }
  MatrixXd Hp = MatrixXd::Zero(3, dim);
  Hp(0, layout::kX) = Hp(1, layout::kY) = Hp(2, layout::kPhi) = 1.0;
  VectorXd rp(3);
  rp << pp.position_noise * pp.position_noise, pp.position_noise * pp.position_noise,
      pp.angle_noise * pp.angle_noise;
  const int part_every =
      pp.present ? std::max(1, static_cast<int>(std::lround(1.0 / (pp.rate * h_)))) : 0;

  // Start: the covariance of a part that has rested at the start for a while (the first
  // knot's maps, every measurement), so it lies on the start's contact manifold.
  MatrixXd Sigma = MatrixXd::Zero(dim, dim);
  auto predict = [&](int k) {
    Sigma = Ad_[k] * Sigma * Ad_[k].transpose();
    Sigma.topLeftCorner(n, n).diagonal() += drift.cwiseAbs2() * h_;
    Sigma += h_ * F_[k] * Sf * F_[k].transpose();
    for (int c = 0; c < layout::kObjectDim; ++c)
      Sigma(n + c, n + c) += s.noise.slip_acceleration * s.noise.slip_acceleration * h_;
  };
  auto update = [&](const MatrixXd& H, const VectorXd& r, bool apply) {
    const MatrixXd SH = Sigma * H.transpose();
    MatrixXd Sm = H * SH;
    Sm.diagonal() += r;
    MatrixXd L = Sm.ldlt().solve(SH.transpose()).transpose();
    if (apply) {
      Sigma -= L * SH.transpose();
      symmetrize(Sigma);
    }
    return L;
  };
  const long warmup = std::lround(1.0 / h_);
  for (long j = 0; j < warmup; ++j) {
    update(Hj, rj, true);
    if (pp.present && j % part_every == 0) update(Hp, rp, true);
    predict(0);
  }
  const int knots = numKnots();
  Lj_.assign(knots, MatrixXd());
  Lp_.assign(knots, MatrixXd());
  long step = 0;
  for (int k = 0; k < knots; ++k) {
    for (int j = 0; j < steps_per_knot_; ++j, ++step) {
      MatrixXd L = update(Hj, rj, true);
      if (j == 0) Lj_[k] = std::move(L);
      if (pp.present) {
        L = update(Hp, rp, step % part_every == 0);
        if (j == 0) Lp_[k] = std::move(L);
      }
      predict(k);
    }
  }
}

}  // namespace rbsf
