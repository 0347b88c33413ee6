#include "rbsf/dynamics/core/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {
namespace {

using layout::kPhi;
using layout::kTheta;
using layout::kX;
using layout::kY;

// Gap and anchor errors below this need no correction [m].
constexpr double kDriftFloor = 1e-13;

/// Configuration index and range of the mechanism coordinate k (0: theta, k >= 1: stroke).
void limitOf(const Cell& cell, int k, int& index, double& lo, double& hi) {
  if (k == 0) {
    index = kTheta;
    lo = cell.base.theta_min;
    hi = cell.base.theta_max;
  } else {
    index = layout::stroke(k - 1);
    lo = cell.fingers[k - 1].stroke_min;
    hi = cell.fingers[k - 1].stroke_max;
  }
}

/// x = A^-1 r for a symmetric positive definite A (n x n, lower Cholesky in place).
void choleskySolve(MatII& A, VecI& r, int n) {
  for (int j = 0; j < n; ++j) {
    double d = A(j, j);
    for (int k = 0; k < j; ++k) d -= A(j, k) * A(j, k);
    d = std::sqrt(std::max(d, std::numeric_limits<double>::min()));
    A(j, j) = d;
    for (int i = j + 1; i < n; ++i) {
      double s = A(i, j);
      for (int k = 0; k < j; ++k) s -= A(i, k) * A(j, k);
      A(i, j) = s / d;
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) r[i] -= A(i, k) * r[k];
    r[i] /= A(i, i);
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k < n; ++k) r[i] -= A(k, i) * r[k];
    r[i] /= A(i, i);
  }
}

}  // namespace

std::string_view toString(ContactMode mode) {
  switch (mode) {
    case ContactMode::kStick:
      return "stick";
    case ContactMode::kSlide:
      return "slide";
    case ContactMode::kSeparated:
      return "separated";
  }
  return "?";
}

SimState::SimState(const VecQ& q_, const VecQ& v_) : q(q_), v(v_) {
  const int m = static_cast<int>(q.size()) - 4;
  if (m < 1 || m > kMaxFingers || v.size() != q.size())
    throw InputError("SimState: q and v must both have m + 4 entries, 1 <= m <= " +
                     std::to_string(kMaxFingers));
  xi_hint = VecC::Constant(m, std::numeric_limits<double>::quiet_NaN());
  slip = VecC::Zero(m);
  mode.fill(ContactMode::kSeparated);
  friction_guess.fill(FrictionMode::kStick);
  anchored.fill(false);
  anchor.fill(Vec2::Zero());
  limit_closed.fill(false);
}

SimulatorWorkspace::SimulatorWorkspace(int m)
    : data(m),
      acc(VecQ::Zero(m + 4)),
      v_free(VecQ::Zero(m + 4)),
      dq(VecQ::Zero(m + 4)),
      W(m + 4, 0),
      MinvW(m + 4, 0) {}

Simulator::Simulator(const RbsfModel& model, const SimulatorSettings& s)
    : model_(model), settings_(s) {
  checkSettings(s);
}

void Simulator::checkSettings(const SimulatorSettings& s) {
  if (!(std::isfinite(s.time_step) && s.time_step > 0.0))
    throw InputError("simulator: time step must be positive and finite");
  if (!(s.contact_tolerance >= 0.0 && s.activation_distance >= s.contact_tolerance &&
        std::isfinite(s.activation_distance)))
    throw InputError("simulator: need 0 <= contact_tolerance <= activation_distance < inf");
  if (!(s.slip_tolerance >= 0.0 && s.regularization >= 0.0 && s.max_mode_iterations >= 0))
    throw InputError("simulator: tolerances and iteration counts must be non-negative");
}

int Simulator::assembleRows(const SimState& state, SimulatorWorkspace& ws) const {
  const Cell& cell = model_.cell();
  const int m = model_.numFingers();
  const double act = settings_.activation_distance, h = settings_.time_step;
  // A row enters the step when its gap, or the gap it would reach within the step moving
  // freely, is within the activation distance: fast approaches cannot tunnel through.
  auto active = [&](double gap, double free_rate) {
    return gap + h * std::min(0.0, free_rate) <= act;
  };
  int nc = 0;
  for (int i = 0; i < m; ++i)
    if (active(ws.data.contacts[i].gap, ws.data.G1.col(i).dot(ws.v_free)))
      ws.contact_finger[nc++] = i;
  int nl = 0;
  ws.gap.resize(nc + 2 * (m + 1));
  for (int k = 0; k <= m; ++k) {
    int index;
    double lo, hi;
    limitOf(cell, k, index, lo, hi);
    const double q = state.q[index], rate = ws.v_free[index];
    if (active(q - lo, rate)) ws.limit_index[nl] = 2 * k, ws.gap[nc + nl++] = q - lo;
    if (active(hi - q, -rate)) ws.limit_index[nl] = 2 * k + 1, ws.gap[nc + nl++] = hi - q;
  }
  const int nu = nc + nl, nr = nu + nc;
  ws.solver.resize(nc, nl);
  ws.W.setZero(model_.configDim(), nr);
  for (int r = 0; r < nc; ++r) {
    const int i = ws.contact_finger[r];
    ws.W.col(r) = ws.data.G1.col(i);
    ws.W.col(nu + r) = ws.data.T.col(i);
    ws.gap[r] = ws.data.contacts[i].gap;
  }
  for (int j = 0; j < nl; ++j) {
    int index;
    double lo, hi;
    limitOf(cell, ws.limit_index[j] / 2, index, lo, hi);
    ws.W(index, nc + j) = ws.limit_index[j] % 2 == 0 ? 1.0 : -1.0;
  }
  ws.MinvW = ws.W;
  model_.applyMassInverse(state.q, ws.MinvW);
  ws.solver.D.noalias() = ws.W.transpose() * ws.MinvW;
  ws.solver.b.noalias() = ws.W.transpose() * ws.v_free;

  const FrictionParams& fr = cell.friction;
  for (int u = 0; u < nu; ++u) {
    ws.open_row[u] = ws.gap[u] > settings_.contact_tolerance;
    if (ws.open_row[u]) ws.solver.b[u] += ws.gap[u] / h;
  }
  for (int r = 0; r < nc; ++r) {
    const int i = ws.contact_finger[r];
    if (settings_.curvature_terms) {
      ws.solver.b[r] += 0.5 * h * ws.data.h_n[i];
      ws.solver.b[nu + r] += 0.5 * h * ws.data.h_t[i];
    }
    ws.solver.mu[r] = state.mode[i] == ContactMode::kSlide ? fr.mu_kinetic : fr.mu_static;
    ws.solver.closed[r] = state.mode[i] != ContactMode::kSeparated || !ws.open_row[r];
    // A sticking contact is guessed sticking (inside its cone): among the indeterminate
    // stick forces the regularised solve then returns the least-norm ones whenever they fit
    // the cones, instead of keeping a contact at its cone edge because it was there before.
    ws.solver.friction[r] =
        state.mode[i] == ContactMode::kSlide ? state.friction_guess[i] : FrictionMode::kStick;
  }
  for (int j = 0; j < nl; ++j)
    ws.solver.closed[nc + j] = state.limit_closed[ws.limit_index[j]] || !ws.open_row[nc + j];
  ws.solver.regularization = settings_.regularization;
  ws.solver.max_mode_iterations = settings_.max_mode_iterations;
  return nc;
}

void Simulator::correctDrift(const SimState& state, SimulatorWorkspace& ws) const {
  ContactImpulseSolver& s = ws.solver;
  const int nc = s.numContacts(), nu = s.numUnilateral();
  int n = 0;
  ws.ec.resize(s.numRows());
  for (int u = 0; u < nu; ++u) {
    if (ws.open_row[u] || !s.closed[u]) continue;
    ws.corr_row[n] = u;
    ws.ec[n++] = ws.gap[u];
  }
  const double c = std::cos(state.q[kPhi]), sn = std::sin(state.q[kPhi]);
  const Vec2 x_o(state.q[kX], state.q[kY]);
  for (int r = 0; r < nc; ++r) {
    const int i = ws.contact_finger[r];
    if (ws.open_row[r] || !s.closed[r] || !state.anchored[i] ||
        s.friction[r] != FrictionMode::kStick)
      continue;
    const ContactFrame& f = ws.data.contacts[i];
    const Vec2& a = state.anchor[i];
    const Vec2 stuck = x_o + Vec2(c * a.x() - sn * a.y(), sn * a.x() + c * a.y());
    ws.corr_row[n] = nu + r;
    ws.ec[n++] = f.tangent.dot(stuck - f.tip);
  }
  ws.dq.setZero(model_.configDim());
  // Errors at rounding level need no correction (the common case at rest).
  if (n == 0 || ws.ec.head(n).cwiseAbs().maxCoeff() < kDriftFloor) return;
  ws.Dc.resize(n, n);
  ws.ec.conservativeResize(n);
  if (!settings_.drift_moves_part_only) {
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) ws.Dc(a, b) = s.D(ws.corr_row[a], ws.corr_row[b]);
    choleskySolve(ws.Dc, ws.ec, n);
    for (int a = 0; a < n; ++a) ws.dq.noalias() -= ws.ec[a] * ws.MinvW.col(ws.corr_row[a]);
    return;
  }
  // The part alone, weighted by its mass block diag(m, m, I): the M-least correction with
  // the joints held. Slightly damped, since two rows may leave the part one motion.
  const ObjectParams& o = model_.cell().object;
  const Eigen::Vector3d w(1.0 / o.mass, 1.0 / o.mass, 1.0 / o.inertia);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      ws.Dc(a, b) = ws.W.col(ws.corr_row[a])
                        .head<3>()
                        .cwiseProduct(w)
                        .dot(ws.W.col(ws.corr_row[b]).head<3>());
  ws.Dc.diagonal().array() += 1e-9 * ws.Dc.diagonal().maxCoeff();
  choleskySolve(ws.Dc, ws.ec, n);
  for (int a = 0; a < n; ++a)
    ws.dq.head<3>() -= ws.ec[a] * w.cwiseProduct(ws.W.col(ws.corr_row[a]).head<3>());
}

ContactMode Simulator::classify(const SimulatorWorkspace& ws, int r,
                                const VecC* slip_tolerance) const {
  // Touching: in the closed set of the solution, or resting on the part without load
  // (gap at the end of the step, to second order, within the contact tolerance).
  const ContactImpulseSolver& s = ws.solver;
  const int nu = s.numUnilateral();
  const double end_gap = (ws.open_row[r] ? 0.0 : ws.gap[r]) + settings_.time_step * s.y[r];
  if (!s.closed[r] && end_gap > settings_.contact_tolerance) return ContactMode::kSeparated;
  const double slip =
      slip_tolerance ? (*slip_tolerance)[ws.contact_finger[r]] : settings_.slip_tolerance;
  return std::abs(s.y[nu + r]) > slip ? ContactMode::kSlide : ContactMode::kStick;
}

bool Simulator::switchFriction(const SimState& state, SimulatorWorkspace& ws, int nc,
                               const VecC* slip_tolerance) const {
  const FrictionParams& fr = model_.cell().friction;
  if (fr.mu_kinetic == fr.mu_static) return false;
  ContactImpulseSolver& s = ws.solver;
  const int nu = s.numUnilateral();
  bool resolve = false;
  for (int r = 0; r < nc; ++r) {
    const int i = ws.contact_finger[r];
    const ContactMode was = state.mode[i], now = classify(ws, r, slip_tolerance);
    if (now == ContactMode::kSlide && was != ContactMode::kSlide) {
      s.mu[r] = fr.mu_kinetic;  // static friction broke: slide with mu_k from now on
      resolve = true;
    } else if (was == ContactMode::kSlide && now != ContactMode::kSeparated &&
               (now == ContactMode::kStick || s.y[nu + r] * state.slip[i] < 0.0)) {
      s.mu[r] = fr.mu_static;  // the slip stopped or reversed within the step: may stick
      resolve = true;
    }
  }
  return resolve;
}

void Simulator::integrate(SimState& state, SimulatorWorkspace& ws) const {
  const ContactImpulseSolver& s = ws.solver;
  const double h = settings_.time_step;
  state.v = ws.v_free;
  if (s.numRows() > 0) state.v.noalias() += ws.MinvW * s.lambda;
  if (settings_.drift_correction && s.numRows() > 0) correctDrift(state, ws);
  state.q += h * state.v;
  if (settings_.drift_correction && s.numRows() > 0) state.q += ws.dq;
  state.t += h;
  state.xi_hint = ws.data.xi_hint;
}

void Simulator::recordContacts(SimState& state, const SimulatorWorkspace& ws, int nc,
                               double phi_start, StepReport* report,
                               const VecC* slip_tolerance) const {
  const int m = model_.numFingers();
  const ContactImpulseSolver& s = ws.solver;
  const int nu = s.numUnilateral();
  const double h = settings_.time_step;
  std::array<int, kMaxFingers> row_of;
  row_of.fill(-1);
  for (int r = 0; r < nc; ++r) row_of[ws.contact_finger[r]] = r;
  int touching = 0, sticking = 0;
  for (int i = 0; i < m; ++i) {
    const int r = row_of[i];
    const ContactMode mode = r < 0 ? ContactMode::kSeparated : classify(ws, r, slip_tolerance);
    const double slip = mode == ContactMode::kSeparated ? 0.0 : s.y[nu + r];
    // A contact held inside its cone (y_t = 0 exactly) is anchored at the material point
    // under its tip. One at the cone's edge creeps (by less than the slip tolerance, so it
    // still counts as sticking): correcting it back to an anchor would fight the friction
    // law, so it is re-anchored once it holds again.
    const bool held = r >= 0 && s.closed[r] && s.friction[r] == FrictionMode::kStick;
    if (held && !state.anchored[i]) state.anchor[i] = rotate(-phi_start, ws.data.contacts[i].lever);
    state.anchored[i] = held;
    state.mode[i] = mode;
    state.slip[i] = slip;
    state.friction_guess[i] = r < 0 ? FrictionMode::kStick : s.friction[r];
    touching += mode != ContactMode::kSeparated ? 1 : 0;
    sticking += mode == ContactMode::kStick ? 1 : 0;
    if (report) {
      ContactStepReport& c = report->contacts[i];
      c.mode = mode;
      c.f_n = r < 0 ? 0.0 : s.lambda[r] / h;
      // The solvers keep lambda_n >= 0 up to rounding: a closed contact without load can
      // come out at -3e-35 N, which would read as pulling wherever f_n >= 0 is checked.
      // Rounding (under a nanonewton) reads 0; anything more negative is shown as it is.
      if (c.f_n < 0.0 && c.f_n > -1e-9) c.f_n = 0.0;
      c.f_t = r < 0 ? 0.0 : s.lambda[nu + r] / h;
      c.gap = ws.data.contacts[i].gap;
      c.slip = slip;
    }
  }
  if (report) {
    report->touching = touching;
    report->sticking = sticking;
    report->phase = touching == 0   ? Phase::kUnsupported
                    : sticking >= 2 ? Phase::kC
                    : sticking == 1 ? Phase::kP
                                    : Phase::kU;
  }
}

void Simulator::recordLimits(SimState& state, const SimulatorWorkspace& ws, int nc,
                             StepReport* report) const {
  const ContactImpulseSolver& s = ws.solver;
  state.limit_closed.fill(false);
  for (int j = 0; j < s.numUnilateral() - nc; ++j) {
    state.limit_closed[ws.limit_index[j]] = s.closed[nc + j];
    if (report) {
      int index;
      double lo, hi;
      limitOf(model_.cell(), ws.limit_index[j] / 2, index, lo, hi);
      report->limit_force[index] +=
          (ws.limit_index[j] % 2 == 0 ? 1.0 : -1.0) * s.lambda[nc + j] / settings_.time_step;
    }
  }
}

void Simulator::step(SimState& state, const VecU& tau, SimulatorWorkspace& ws, StepReport* report,
                     const VecC* slip_tolerance) const {
  const int m = model_.numFingers();
  if (state.q.size() != m + 4 || state.v.size() != m + 4 || tau.size() != m + 1 || ws.data.m != m)
    throw std::invalid_argument("Simulator::step: state, tau or workspace sized for another m");
  const double h = settings_.time_step;
  ModelData& d = ws.data;
  d.xi_hint = state.xi_hint;
  model_.updateContacts(state.q, d);
  if (settings_.curvature_terms) model_.velocityProducts(state.q, state.v, d);
  model_.bias(state.q, state.v, d.bias);
  model_.freeAcceleration(state.q, tau, d.bias, ws.acc);
  ws.v_free = state.v + h * ws.acc;

  const int nc = assembleRows(state, ws);
  ContactImpulseSolver& s = ws.solver;
  ImpulseSolvePath path = s.solve();
  const bool resolve = switchFriction(state, ws, nc, slip_tolerance);
  if (resolve) {
    const ImpulseSolvePath second = s.solve();
    if (second > path) path = second;
  }

  const double phi_start = state.q[kPhi];
  integrate(state, ws);
  if (report) {
    report->limit_force.setZero(model_.configDim());
    report->path = path;
    report->resolved = resolve;
  }
  recordContacts(state, ws, nc, phi_start, report, slip_tolerance);
  recordLimits(state, ws, nc, report);
}

}  // namespace rbsf
