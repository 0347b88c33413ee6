#include "rbsf/planner/support/support_trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/plan_reference.h"

namespace rbsf::planner {
namespace {

/// A slip slower than this has no clear direction [m/s].
constexpr double kClearSlip = 1e-3;

/// Quintic rest-to-rest progress s(u), u in [0, 1].
double quintic(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}

/// Catmull-Rom interpolation of waypoints w (uniform parameter), at u in [0, n - 1].
Eigen::VectorXd catmullRom(const std::vector<Eigen::VectorXd>& w, double u) {
  const int n = static_cast<int>(w.size());
  if (n == 1) return w[0];
  u = std::clamp(u, 0.0, static_cast<double>(n - 1));
  const int i = std::min(static_cast<int>(u), n - 2);
  const double s = u - i;
  const Eigen::VectorXd& p1 = w[i];
  const Eigen::VectorXd& p2 = w[i + 1];
  const Eigen::VectorXd p0 = i > 0 ? w[i - 1] : 2.0 * p1 - p2;
  const Eigen::VectorXd p3 = i + 2 < n ? w[i + 2] : 2.0 * p2 - p1;
  const double s2 = s * s, s3 = s2 * s;
  return 0.5 * ((2.0 * p1) + (-p0 + p2) * s + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * s2 +
                (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * s3);
}

/// One stretch of the reference being built.
struct Stretch {
  enum Kind { kRun, kFinger, kRamp } kind = kRun;
  ContactSet set;                       ///< the set carrying the part
  std::vector<Eigen::VectorXd> points;  ///< run coordinates (kRun)
  JigPose base;                         ///< the pose (kFinger, kRamp) or the run's first
  PivotAnchor anchor;                   ///< pivot runs
  int finger = -1;                      ///< kFinger: the finger that moves
  double from = 0.0, to = 0.0;          ///< kFinger: its strokes
  VecU tau_from, tau_to;                ///< kRamp: the inputs at both ends
  ContactSet before, next;              ///< kRamp: the sets before and after it
  double duration = 0.0;
  std::size_t first_step = 0, last_step = 0;  ///< SupportRun
  bool end = false;                           ///< the final rest
};

Eigen::VectorXd runCoordinates(const SupportStep& s) {
  switch (s.set.phase()) {
    case Phase::kU:
      return Eigen::Vector4d(s.pose.X, s.pose.Y, s.pose.psi, s.pose.theta);
    case Phase::kP:
      return Eigen::Vector3d(s.pose.psi, s.pose.theta, s.anchor.stroke);
    default:
      return Eigen::Vector2d(s.pose.theta, s.pose.Y);
  }
}

JigPose runPose(const Stretch& r, const SupportGeometry& g, const Eigen::VectorXd& c) {
  switch (r.set.phase()) {
    case Phase::kU:
      return JigPose{c[0], c[1], c[2], c[3]};
    case Phase::kP: {
      PivotAnchor a = r.anchor;
      a.stroke = c[2];
      return g.pivotPose(a, c[0], c[1]);
    }
    default:
      return JigPose{r.base.X, c[1], r.base.psi, c[0]};
  }
}

/// Builds the reference of a support path: first its stretches (the rests at both ends, the
/// runs and, between them, the hand-overs), then the knots and input pieces over them.
class ReferenceBuilder {
 public:
  ReferenceBuilder(const RbsfModel& model, SupportGeometry& geometry, const SupportPath& path,
                   const SupportTiming& timing)
      : model_(model),
        geometry_(geometry),
        path_(path),
        timing_(timing),
        m_(model.numFingers()),
        balancer_(model, geometry.settings().balance),
        data_(m_) {}

  /// The stretches of the whole path, in time order.
  void addStretches();
  /// The reference over the stretches; `runs`, when given, receives them.
  ReferenceTrajectory knots(std::vector<SupportRun>* runs);

 private:
  std::optional<VecQ> reach(const Stretch& r, double s) const;
  VecQ configuration(const Stretch& r, double s) const;
  VecU staticTau(const JigPose& pose, const ContactSet& set);
  void addHold(std::size_t step, double duration, bool end);
  void addRun(std::size_t a, std::size_t b);
  void addHandover(std::size_t i);
  void addFingerMove(const ContactSet& carrier, const JigPose& pose, int f, double a, double b,
                     std::size_t i);
  ContactRoles rolesOf(const Stretch& r);
  ContactRoles rolesAt(ContactRoles roles, const VecQ& q, const VecQ& v);
  void addKnots(const Stretch& r);

  const RbsfModel& model_;
  SupportGeometry& geometry_;
  const SupportPath& path_;
  const SupportTiming& timing_;
  const int m_;
  ContactBalancer balancer_;
  ModelData data_;
  std::vector<Stretch> stretches_;
  // The reference as knots() builds it.
  ReferenceTrajectory ref_;
  double t0_ = 0.0;  ///< the start of the stretch at hand [s]
  VecU tau_prev_;    ///< the input at the last knot
  bool first_knot_ = true;
};

// The configuration of a stretch at progress s in [0, 1]; nothing when the stretch leaves the
// jig there.
std::optional<VecQ> ReferenceBuilder::reach(const Stretch& r, double s) const {
  JigPose pose = r.base;
  if (r.kind == Stretch::kRun)
    pose = runPose(r, geometry_, catmullRom(r.points, s * (r.points.size() - 1.0)));
  std::optional<VecQ> q = geometry_.configuration(pose, r.set, false);
  if (q && r.kind == Stretch::kFinger)
    (*q)[layout::stroke(r.finger)] = r.from + s * (r.to - r.from);
  return q;
}

// reach(), which must be inside the jig.
VecQ ReferenceBuilder::configuration(const Stretch& r, double s) const {
  const std::optional<VecQ> q = reach(r, s);
  if (!q) throw SupportReferenceError(r.first_step, r.last_step);
  return *q;
}

// The input that holds the part at rest at `pose` on `set`.
VecU ReferenceBuilder::staticTau(const JigPose& pose, const ContactSet& set) {
  const std::optional<VecQ> q = geometry_.configuration(pose, set, false);
  return balancer_.statics(*q, set, data_).tau;
}

void ReferenceBuilder::addStretches() {
  if (timing_.settle_time > 0.0)  // the start at rest under the first set's forces
    addHold(0, timing_.settle_time, false);
  std::size_t i = 0;
  while (i < path_.steps.size()) {
    std::size_t j = i;
    while (j + 1 < path_.steps.size() && path_.steps[j + 1].set == path_.steps[i].set) ++j;
    if (i > 0 && !stretches_.empty()) addHandover(i);
    if (j > i) addRun(i, j);  // a set held at one pose alone has no run
    i = j + 1;
  }
  if (timing_.end_rest > 0.0)  // the end at rest under the last set's forces
    addHold(path_.steps.size() - 1, timing_.end_rest, true);
}

// The part at rest at the path's step `step` under its set's forces for `duration`; `end`:
// the final rest.
void ReferenceBuilder::addHold(std::size_t step, double duration, bool end) {
  const SupportStep& at = path_.steps[step];
  Stretch hold;
  hold.kind = Stretch::kRamp;
  hold.set = hold.before = hold.next = at.set;
  hold.base = at.pose;
  hold.tau_from = hold.tau_to = staticTau(hold.base, hold.set);
  hold.duration = duration;
  hold.end = end;
  hold.first_step = hold.last_step = step;
  stretches_.push_back(hold);
}

// The run of steps a..b (one set), timed by its lengths along the spline. Where the spline
// between valid waypoints leaves the jig, the run is split there into runs that rest at the
// waypoints around the interval left, whose own run (two points: a straight line, the motion
// the search checked) stays inside.
void ReferenceBuilder::addRun(std::size_t a, std::size_t b) {
  const SupportStep& first = path_.steps[a];
  Stretch r;
  r.kind = Stretch::kRun;
  r.set = first.set;
  r.base = first.pose;
  r.anchor = first.anchor;
  r.first_step = a;
  r.last_step = b;
  // A remnant step (every coordinate within 1 % of the run's largest step in it: a finish
  // onto the exact goal a hair past the lattice) merges into the waypoint before it. The
  // uniform spline would give it a whole interval's time and, with the tangent of the step
  // before, bend past the end and back, reversing a slider at its run's end. The pair keeps
  // the later step, so the run ends where the path does. Short steps above 1 % keep their
  // interval: merging those moved a certified plan's nominal run, and its trials failed,
  // while their overshoot (7 % of the step before) is one the law carries.
  std::vector<Eigen::VectorXd> all;
  for (std::size_t k = a; k <= b; ++k) all.push_back(runCoordinates(path_.steps[k]));
  Eigen::VectorXd largest = Eigen::VectorXd::Zero(all[0].size());
  for (std::size_t k = 1; k < all.size(); ++k)
    largest = largest.cwiseMax((all[k] - all[k - 1]).cwiseAbs());
  std::vector<std::size_t> at;  // the step of each waypoint
  for (std::size_t k = a; k <= b; ++k) {
    const Eigen::VectorXd& c = all[k - a];
    const bool near = !r.points.empty() &&
                      ((c - r.points.back()).cwiseAbs().array() <= 0.01 * largest.array()).all();
    if (near && r.points.size() > 1) {  // the later step replaces the one before it
      r.points.back() = c;
      at.back() = k;
      continue;
    }
    if (near && k < b) continue;  // the run's first waypoint stays
    r.points.push_back(c);
    at.push_back(k);
  }
  // Lengths along the spline: the part's travel and turn, the base's, the strokes'.
  double travel = 0.0, turn = 0.0, base = 0.0, stroke = 0.0;
  const int fine = 8 * static_cast<int>(r.points.size());
  VecQ prev = configuration(r, 0.0);
  for (int k = 1; k <= fine; ++k) {
    const double s = static_cast<double>(k) / fine;
    const std::optional<VecQ> q = reach(r, s);
    if (!q) {
      const std::size_t n = r.points.size();
      if (n == 2) throw SupportReferenceError(a, b);
      const std::size_t w = std::min(static_cast<std::size_t>(s * (n - 1)), n - 2);
      const std::size_t left = at[w], right = at[w + 1];  // the interval's ends
      if (left > a) addRun(a, left);
      addRun(left, right);
      if (b > right) addRun(right, b);
      return;
    }
    const VecQ dq = *q - prev;
    travel += std::hypot(dq[layout::kX], dq[layout::kY]);
    turn += std::abs(dq[layout::kPhi]);
    base += std::abs(dq[layout::kTheta]);
    stroke += dq.tail(m_).cwiseAbs().maxCoeff();
    prev = *q;
  }
  const double peak = 1.875, peak_acc = 5.7735;
  const double longest = std::max({travel, turn, base});
  r.duration = std::max({timing_.min_run_time, peak * travel / timing_.part_speed,
                         peak * std::max(turn, base) / timing_.angular_speed,
                         peak * stroke / timing_.stroke_speed,
                         std::sqrt(peak_acc * longest / timing_.part_acceleration)});
  stretches_.push_back(r);
}

// The hand-over at step i's pose from the set of the stretch before to step i's set: the
// fingers that join move up alone, the forces ramp from one set's to the other's, and the
// fingers that leave move away alone.
void ReferenceBuilder::addHandover(std::size_t i) {
  const Cell& cell = model_.cell();
  const ContactSet from = stretches_.back().set, to = path_.steps[i].set;
  const JigPose pose = path_.steps[i].pose;
  const std::uint32_t joins = to.touching & ~from.touching;
  const std::uint32_t leaves = from.touching & ~to.touching;
  const std::optional<VecQ> q_to = geometry_.configuration(pose, to, false);
  for (int f = 0; f < m_; ++f)
    if ((joins >> f) & 1u) {
      const double touch = (*q_to)[layout::stroke(f)];
      addFingerMove(from, pose, f, cell.fingers[f].stroke_min, touch, i);
      addFingerMove(from, pose, f, touch, touch, i);
      stretches_.back().duration = timing_.touch_time;
    }
  Stretch ramp;
  ramp.kind = Stretch::kRamp;
  ramp.set = ContactSet{from.touching | to.touching, from.sticking & to.sticking};
  ramp.base = pose;
  ramp.tau_from = staticTau(pose, from);
  ramp.tau_to = staticTau(pose, to);
  ramp.before = from;
  ramp.next = to;
  ramp.duration = timing_.handover_time;
  ramp.first_step = i - 1;
  ramp.last_step = i;
  stretches_.push_back(ramp);
  const std::optional<VecQ> q_from = geometry_.configuration(pose, from, false);
  for (int f = 0; f < m_; ++f)
    if ((leaves >> f) & 1u)
      addFingerMove(to, pose, f, (*q_from)[layout::stroke(f)], cell.fingers[f].stroke_min, i);
}

// Finger f alone strokes from `a` to `b` (rest to rest) at `pose` while `carrier` holds the
// part, in the hand-over at step i.
void ReferenceBuilder::addFingerMove(const ContactSet& carrier, const JigPose& pose, int f,
                                     double a, double b, std::size_t i) {
  Stretch r;
  r.kind = Stretch::kFinger;
  r.set = carrier;
  r.base = pose;
  r.finger = f;
  r.from = a;
  r.to = b;
  r.duration = std::max(timing_.min_run_time, 1.875 * std::abs(b - a) / timing_.stroke_speed);
  r.first_step = i - 1;
  r.last_step = i;
  stretches_.push_back(r);
}

// The contacts' roles over a stretch (contact_roles.h). A run's sliders slide the way its
// middle slips them; at rest the set's sticking contacts stick (its sliders: below); a finger
// whose load a hand-over ramps from or to nothing is not relied on, and one that moves up
// alone to join may touch at its end; the others are lifted.
ContactRoles ReferenceBuilder::rolesOf(const Stretch& r) {
  ContactRoles roles{};
  const VecQ q = configuration(r, 0.5);
  VecQ v = VecQ::Zero(q.size());
  if (r.kind == Stretch::kRun) v = configuration(r, 0.5 + 1e-4) - configuration(r, 0.5 - 1e-4);
  data_.xi_hint.setConstant(std::numeric_limits<double>::quiet_NaN());
  model_.updateContacts(q, data_);
  for (int f = 0; f < m_; ++f) {
    const bool touching = r.set.touches(f);
    if (r.kind == Stretch::kFinger && f == r.finger)
      roles[f] = r.to >= r.from ? ContactRole::kFree : ContactRole::kLifted;
    else if (r.kind == Stretch::kRamp && touching && !(r.before.touches(f) && r.next.touches(f)))
      roles[f] = ContactRole::kFree;
    else if (!touching)
      roles[f] = ContactRole::kLifted;
    else if (r.set.sticks(f))
      roles[f] = ContactRole::kStick;
    else if (r.kind != Stretch::kRun)
      // A slider at rest is stuck but not relied on (its run's balance may hold it near its
      // cone's edge), except beside one other tip in the final rest and while another
      // finger moves alone, where the part must stay at rest and two sticking tips steer
      // their squeeze (among three no actuator steers it).
      roles[f] = (r.end || r.kind == Stretch::kFinger) && r.set.count() <= 2 ? ContactRole::kStick
                                                                             : ContactRole::kFree;
    else
      roles[f] =
          data_.T.col(f).dot(v) < 0.0 ? ContactRole::kSlideNegative : ContactRole::kSlidePositive;
  }
  return roles;
}

// A slider's role at one instant of a run: the way the reference slips it there, where it
// clearly does (else the run's own way).
ContactRoles ReferenceBuilder::rolesAt(ContactRoles roles, const VecQ& q, const VecQ& v) {
  data_.xi_hint.setConstant(std::numeric_limits<double>::quiet_NaN());
  model_.updateContacts(q, data_);
  for (int f = 0; f < m_; ++f) {
    if (slipSign(roles[f]) == 0) continue;
    const double slip = data_.T.col(f).dot(v);
    if (std::abs(slip) > kClearSlip)
      roles[f] = slip < 0.0 ? ContactRole::kSlideNegative : ContactRole::kSlidePositive;
  }
  return roles;
}

ReferenceTrajectory ReferenceBuilder::knots(std::vector<SupportRun>* runs) {
  for (const Stretch& r : stretches_) {
    addKnots(r);
    if (runs != nullptr)
      runs->push_back(SupportRun{t0_, t0_ + r.duration, r.kind == Stretch::kRamp ? r.next : r.set,
                                 r.kind != Stretch::kRun, r.first_step, r.last_step});
    first_knot_ = false;
    t0_ += r.duration;
  }
  return std::move(ref_);
}

// The knots of stretch `r` (from t0_; its first knot only when it is the first stretch) and
// the input pieces that end at them: a ramp's inputs blend its ends', the others balance the
// motion (the last input where the balance has no solution).
void ReferenceBuilder::addKnots(const Stretch& r) {
  const double dt = timing_.knot_interval;
  const int n = std::max(1, static_cast<int>(std::ceil(r.duration / dt - 1e-9)));
  const double step = r.duration / n;
  auto q_at = [&](double t) { return configuration(r, quintic(t / r.duration)); };
  const ContactRoles roles = rolesOf(r);
  for (int k = first_knot_ ? 0 : 1; k <= n; ++k) {
    const double t = k * step, h = std::min(1e-3, 0.25 * step);
    const VecQ q = q_at(t);
    const VecQ v = (q_at(t + h) - q_at(t - h)) / (2.0 * h);
    const VecQ a = (q_at(t + h) - 2.0 * q + q_at(t - h)) / (h * h);
    VecU tau;
    if (r.kind == Stretch::kRamp) {
      const double s = quintic(t / r.duration);
      tau = (1.0 - s) * r.tau_from + s * r.tau_to;
    } else {
      const ContactBalance b = balancer_.solve(q, v, a, r.set, data_);
      tau = b.solvable ? b.tau : (tau_prev_.size() ? tau_prev_ : b.tau);
    }
    ref_.addKnot(t0_ + t, q, v);
    if (!first_knot_ || k > 0) {
      const Phase ph = (r.kind == Stretch::kRamp ? r.next : r.set).phase();
      ref_.addInputPiece(t0_ + (k - 1) * step, step, tau_prev_, tau, ph,
                         r.kind == Stretch::kRun ? rolesAt(roles, q, v) : roles);
    }
    tau_prev_ = tau;
  }
}

}  // namespace

SupportReferenceError::SupportReferenceError(std::size_t first, std::size_t last)
    : std::runtime_error("the support path's steps " + std::to_string(first) + "-" +
                         std::to_string(last) + " leave the jig between waypoints"),
      first_step(first),
      last_step(last) {}

ReferenceTrajectory supportReference(const RbsfModel& model, SupportGeometry& geometry,
                                     const SupportPath& path, const SupportTiming& timing,
                                     std::vector<SupportRun>* runs) {
  if (path.steps.empty()) throw std::invalid_argument("supportReference: empty path");
  ReferenceBuilder builder(model, geometry, path, timing);
  builder.addStretches();
  return builder.knots(runs);
}

double departureTime(const plan::Plan& plan, const ReferenceTrajectory& reference, double position,
                     double angle) {
  ReferenceSample r;
  for (const plan::PlanSample& s : plan.samples) {
    reference.sample(std::clamp(s.t, reference.startTime(), reference.endTime()), r);
    const double dx = s.q[layout::kX] - r.q[layout::kX], dy = s.q[layout::kY] - r.q[layout::kY];
    if (std::hypot(dx, dy) > position || std::abs(s.q[layout::kPhi] - r.q[layout::kPhi]) > angle)
      return s.t;
  }
  return -1.0;
}

plan::Plan closedLoopPlan(const RbsfModel& model, const ReferenceTrajectory& reference,
                          const SimulatorSettings& simulator, const FeedbackSettings& feedback,
                          const Pose& goal, double position_tolerance, double angle_tolerance,
                          int sample_steps, int control_steps) {
  plan::Plan plan;
  plan.joint_feedback = true;
  const FeedbackSchedule schedule(model, reference, lawSensing(model.cell().sensing, plan),
                                  simulator, feedback);
  ControlLaw law(schedule);
  const Simulator sim(model, simulator);
  const double h = simulator.time_step;
  ReferenceSample start;
  reference.sample(reference.startTime(), start);
  SimState state(start.q, VecQ::Zero(start.q.size()));
  SimulatorWorkspace ws(model.numFingers());
  const long steps = std::lround((reference.endTime() - reference.startTime()) / h);
  plan.simulator = simulator;
  plan.q0 = start.q;
  plan.start = Pose{start.q[layout::kX], start.q[layout::kY], start.q[layout::kPhi]};
  plan.start_theta = start.q[layout::kTheta];
  plan.goal = goal;
  plan.steps_per_control = control_steps;
  VecU held;
  rollout(
      sim, state, steps, ws,
      [&](const SimState& now, long n, VecU& tau) {
        if (n % control_steps == 0) {  // the law once per segment, its input held
          const double t = static_cast<double>(n) * h;
          law.computeFromState(t, now.q, now.v, held);
          plan::PlanSegment seg;
          ReferenceSample at;
          reference.sample(t, at);
          seg.contacts = at.roles;
          seg.steps = static_cast<int>(std::min<long>(control_steps, steps - n));
          seg.duration = seg.steps * h;
          seg.tau = held;
          plan.segments.push_back(seg);
        }
        tau = held;
        return true;
      },
      [&](const SimState& now, const StepReport&, const VecU&, long n) {
        return (n + 1) % control_steps != 0 || !fellOff(now.q, start.q);  // at a segment's end
      });
  plan.samples = simulateSegments(sim, plan.q0, plan.segments, sample_steps);
  const plan::PlanSample& last = plan.samples.back();
  const double dx = last.q[layout::kX] - goal.x, dy = last.q[layout::kY] - goal.y;
  const double dphi = std::remainder(last.q[layout::kPhi] - goal.phi, 2.0 * M_PI);
  plan.goal_distance =
      std::max(std::hypot(dx, dy) / position_tolerance, std::abs(dphi) / angle_tolerance);
  plan.status =
      plan.goal_distance <= 1.0 ? plan::PlanStatus::kExact : plan::PlanStatus::kApproximate;
  return plan;
}

}  // namespace rbsf::planner
