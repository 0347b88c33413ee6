#include "rbsf/trajopt/decision_variables.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/optimizer_settings.h"

namespace rbsf::trajopt {

DecisionVariables::DecisionVariables(const RbsfModel& model, const DecisionLayout& layout,
                                     const Schedule& schedule, const plan::Plan& plan,
                                     const OptimizerSettings& settings)
    : model_(model),
      layout_(layout),
      schedule_(schedule),
      plan_(plan),
      min_scale_(settings.duration_min_scale),
      max_scale_(settings.duration_max_scale),
      normal_floor_(settings.normal_floor * model.cell().object.mass *
                    std::max(model.cell().gravity, 1.0)),
      motion_limits_(settings.motion_limits),
      keep_end_rest_(settings.keep_end_rest),
      cone_(settings.cone_margin),
      tube_position_(settings.tube_position),
      tube_angle_(settings.tube_angle) {
  const double final_phi = plan.samples.back().q[layout::kPhi];
  goal_phi_ = final_phi + std::remainder(plan.goal.phi - final_phi, 2.0 * M_PI);
  planned_ = plannedGuess();
}

void DecisionVariables::bounds(Eigen::VectorXd& lower, Eigen::VectorXd& upper) const {
  const Cell& cell = model_.cell();
  const int m = model_.numFingers(), n = model_.configDim(), K = layout_.knots();
  lower = Eigen::VectorXd::Constant(layout_.size(), -kInfinity);
  upper = Eigen::VectorXd::Constant(layout_.size(), kInfinity);
  for (int k = 0; k < K; ++k) {
    lower[layout_.q(k) + layout::kTheta] = cell.base.theta_min;
    upper[layout_.q(k) + layout::kTheta] = cell.base.theta_max;
    lower[layout_.tau(k) + layout::kTauTheta] = -cell.base.torque_limit;
    upper[layout_.tau(k) + layout::kTauTheta] = cell.base.torque_limit;
    for (int i = 0; i < m; ++i) {
      const FingerParams& f = cell.fingers[i];
      lower[layout_.q(k) + layout::stroke(i)] = f.stroke_min;
      upper[layout_.q(k) + layout::stroke(i)] = f.stroke_max;
      lower[layout_.tau(k) + layout::fingerForce(i)] = -f.force_limit;
      upper[layout_.tau(k) + layout::fingerForce(i)] = f.force_limit;
      const ContactRole role = schedule_.forceRole(k, i);
      const bool relied = schedule_.runOf(std::min(k, layout_.intervals() - 1)).relied[i];
      lower[layout_.fn(k) + i] = role != ContactRole::kOff && relied ? normal_floor_ : 0.0;
      upper[layout_.fn(k) + i] = role == ContactRole::kOff ? 0.0 : kInfinity;
      if (role != ContactRole::kStick) lower[layout_.ft(k) + i] = upper[layout_.ft(k) + i] = 0.0;
    }
  }
  // The tube: every knot's configuration near the plan's at the same share of its run.
  for (int k = 0; k < K; ++k)
    for (int a = 0; a < n; ++a) {
      const bool angle = a == layout::kPhi || a == layout::kTheta;
      const double r = angle ? tube_angle_ : tube_position_;
      if (!(r > 0.0)) continue;
      const int c = layout_.q(k) + a;
      lower[c] = std::max(lower[c], planned_[c] - r);
      upper[c] = std::min(upper[c], planned_[c] + r);
    }
  if (motion_limits_) {
    const MotionLimits& ml = cell.motion_limits;
    const double axis = ml.part_speed / std::sqrt(2.0);
    for (int k = 0; k < K; ++k) {
      for (int a : {layout::kX, layout::kY}) {
        lower[layout_.v(k) + a] = -axis;
        upper[layout_.v(k) + a] = axis;
      }
      lower[layout_.v(k) + layout::kPhi] = -ml.angular_speed;
      upper[layout_.v(k) + layout::kPhi] = ml.angular_speed;
    }
  }
  for (int a = 0; a < n; ++a) {
    lower[layout_.q(0) + a] = upper[layout_.q(0) + a] = plan_.q0[a];
    lower[layout_.v(0) + a] = upper[layout_.v(0) + a] = 0.0;
    lower[layout_.v(K - 1) + a] = upper[layout_.v(K - 1) + a] = 0.0;
  }
  const double goal[3] = {plan_.goal.x, plan_.goal.y, goal_phi_};
  for (int a = 0; a < layout::kObjectDim; ++a)
    lower[layout_.q(K - 1) + a] = upper[layout_.q(K - 1) + a] = goal[a];
  for (int j = 0; j < layout_.runs(); ++j) {
    lower[layout_.duration(j)] = min_scale_ * schedule_.runs[j].duration;
    upper[layout_.duration(j)] = max_scale_ * schedule_.runs[j].duration;
  }
  // The plan's end rest stays a rest, as long as planned: the law settles the part there.
  // Its pose alone is fixed: with the velocities fixed too, the -30 degree refinement took
  // 101 Ipopt iterations instead of 25 (the collocation then leaves them of order h dv/dt).
  const PhaseRun& last = schedule_.runs.back();
  if (keep_end_rest_ && last.at_rest) {
    for (int k = last.first_interval; k < K; ++k)
      for (int a = 0; a < layout::kObjectDim; ++a)
        lower[layout_.q(k) + a] = upper[layout_.q(k) + a] = goal[a];
    const int j = layout_.runs() - 1;
    lower[layout_.duration(j)] = std::max(lower[layout_.duration(j)], last.duration);
  }
}

Eigen::VectorXd DecisionVariables::scaling() const {
  const Cell& cell = model_.cell();
  const int m = model_.numFingers();
  const double w_o = cell.object.mass * std::max(cell.gravity, 1.0);
  Eigen::VectorXd s = Eigen::VectorXd::Ones(layout_.size());
  for (int k = 0; k < layout_.knots(); ++k) {
    s[layout_.tau(k) + layout::kTauTheta] = 1.0 / cell.base.torque_limit;
    for (int i = 0; i < m; ++i) {
      s[layout_.tau(k) + layout::fingerForce(i)] = 1.0 / cell.fingers[i].force_limit;
      s[layout_.fn(k) + i] = s[layout_.ft(k) + i] = 1.0 / w_o;
    }
  }
  for (int j = 0; j < layout_.runs(); ++j)
    s[layout_.duration(j)] = 1.0 / schedule_.runs[j].duration;
  return s;
}

double DecisionVariables::knotTime(const Eigen::Ref<const Eigen::VectorXd>& z, int k) const {
  double t = 0.0;
  for (int j = 0; j < layout_.runs(); ++j) {
    const PhaseRun& run = schedule_.runs[j];
    const double T = z[layout_.duration(j)];
    if (k <= run.first_interval + run.intervals)
      return t + T * (k - run.first_interval) / run.intervals;
    t += T;
  }
  return t;
}

Eigen::VectorXd DecisionVariables::initialGuess() const {
  Eigen::VectorXd lower, upper;
  bounds(lower, upper);
  Eigen::VectorXd z = planned_.cwiseMax(lower).cwiseMin(upper);
  // Tangential forces into the cone the solution keeps (FrictionConeConstraint): the
  // simulator's mean forces over a hand-over left one 14.5 N outside it in the -45 degree
  // plan, and Ipopt took 55 iterations (its restoration phase) instead of 29.
  const double mu = cone_ * model_.cell().friction.mu_static;
  for (int k = 0; k < layout_.knots(); ++k)
    for (int i = 0; i < model_.numFingers(); ++i) {
      const double limit = mu * z[layout_.fn(k) + i];
      double& ft = z[layout_.ft(k) + i];
      ft = std::clamp(ft, -limit, limit);
    }
  return z;
}

Eigen::VectorXd DecisionVariables::plannedGuess() const {
  const int m = model_.numFingers(), n = model_.configDim(), nu = model_.controlDim();
  const int K = layout_.knots(), N = layout_.intervals();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(layout_.size());
  for (int j = 0; j < layout_.runs(); ++j) z[layout_.duration(j)] = schedule_.runs[j].duration;
  std::vector<double> knot_t(K);
  for (int k = 0; k < K; ++k) knot_t[k] = knotTime(z, k);

  // The contact impulses of each knot's share of time, [mid_k-1, mid_k] with mid_k the
  // midpoint of interval k (the ends clamped to the plan), from the schedule's
  // re-simulation (the simulator's forces times its step), so that a knot force is the
  // mean over the time the collocation integrates it, impacts included.
  const SimulatedSteps& steps = schedule_.steps;
  const std::vector<double>& ts = steps.t;
  auto mid = [&](int k) { return 0.5 * (knot_t[k] + knot_t[k + 1]); };
  Eigen::MatrixXd impulse_n = Eigen::MatrixXd::Zero(m, K), impulse_t = impulse_n;
  int bin = 0;
  for (std::size_t j = 0; j < steps.contacts.size(); ++j) {
    const double h = ts[j + 1] - ts[j];
    while (bin < N && ts[j] + 0.5 * h >= mid(bin)) ++bin;
    for (int i = 0; i < m; ++i) {
      impulse_n(i, bin) += h * steps.contacts[j][i].f_n;
      impulse_t(i, bin) += h * steps.contacts[j][i].f_t;
    }
  }

  ModelData data(m);
  VecC prev_xi(m);
  std::size_t s = 0;
  for (int k = 0; k < K; ++k) {
    const double tk = knot_t[k];
    while (s + 2 < ts.size() && ts[s + 1] <= tk) ++s;
    const std::size_t s1 = std::min(s + 1, ts.size() - 1);
    const double w = ts[s1] > ts[s] ? std::clamp((tk - ts[s]) / (ts[s1] - ts[s]), 0.0, 1.0) : 0.0;
    const VecQ q = (1.0 - w) * steps.q[s] + w * steps.q[s1];
    z.segment(layout_.q(k), n) = q;
    z.segment(layout_.v(k), n) = (1.0 - w) * steps.v[s] + w * steps.v[s1];
    const double share = (k < N ? mid(k) : knot_t[N]) - (k > 0 ? mid(k - 1) : knot_t[0]);
    z.segment(layout_.fn(k), m) = impulse_n.col(k) / share;
    z.segment(layout_.ft(k), m) = impulse_t.col(k) / share;
    // tau: the segment that is held from t on.
    double seg_start = 0.0;
    const plan::PlanSegment* seg = &plan_.segments.back();
    for (const plan::PlanSegment& sg : plan_.segments) {
      if (tk < seg_start + sg.duration - 1e-12) {
        seg = &sg;
        break;
      }
      seg_start += sg.duration;
    }
    z.segment(layout_.tau(k), nu) = seg->tau;
    model_.updateContacts(q, data);
    for (int i = 0; i < m; ++i) {
      double xi = data.contacts[i].xi;
      if (k > 0) xi = prev_xi[i] + std::remainder(xi - prev_xi[i], 2.0 * M_PI);
      prev_xi[i] = xi;
      z[layout_.xi(k) + i] = xi;
    }
  }
  return z;
}

}  // namespace rbsf::trajopt
