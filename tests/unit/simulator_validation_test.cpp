// The simulator against the acceleration-level analysis: the tilt at which a held part
// starts to slide, and the phase-U contact forces as the step shrinks.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/stick_dynamics.h"
#include "sim_test_support.h"

namespace rbsf {
namespace {

using layout::kTauTheta;
using layout::kTheta;
using test::ShapeKind;

// Why two fingers. With m >= 3 sticking contacts the contact forces are statically
// indeterminate (paper 2.2: the 2m contact rows have rank m + 2), so the tilt at which a
// contact leaves its cone depends on how the indeterminate part is chosen, and a rigid model
// cannot predict it unambiguously. With m = 2 the rows have full rank 4 and, once tau is
// known, the sticking forces are unique. In the test the strokes are held by a PD; while
// both contacts stick the strokes can only move together (the common stroke of phase C),
// so the PD adds the same force c to both fingers and the finger forces are
// tau0_i + c with unknown c. At rest on the rigidly tilted configuration the analysis then
// gives, for each tilt: solvePhaseC() forces and accelerations are affine in (tau_theta, c);
// choosing both so that the base and the common stroke do not accelerate leaves one
// static solution, whose cone margin min_i(mu f_n,i - |f_t,i|) decides the onset.

Cell twoFingerCell() {
  Cell c = test::makeCell(ShapeKind::kEllipse, 2);
  c.fingers[0].r = -0.12;  // contacts at different heights on the shifted ellipse, so that
  c.fingers[1].r = 0.16;   // the two finger axes load the contacts independently
  for (FingerParams& f : c.fingers) f.com_offset = 0.0, f.inertia = 0.0, f.mass = 2.0;
  c.friction = {0.6, 0.0};
  return c;
}

struct StaticForces {
  Eigen::VectorXd fn, ft;
  double margin = 0.0;  // min_i (mu f_n,i - |f_t,i|) [N]
};

StaticForces staticForces(const RbsfModel& model, const VecQ& q0, const VecU& tau0, double tilt) {
  const int m = model.numFingers();
  const VecQ q = test::turnedWithBase(q0, tilt);
  const VecQ v = VecQ::Zero(m + 4);
  ModelData d(m);
  model.updateContacts(q, d);
  VecU ta = tau0, tb, tc;
  ta[kTauTheta] = 0.0;
  tb = ta, tc = ta;
  tb[kTauTheta] += 1.0;
  for (int i = 0; i < m; ++i) tc[layout::fingerForce(i)] += 1.0;
  const StickSolution a = solvePhaseC(model, q, v, ta, d), b = solvePhaseC(model, q, v, tb, d),
                      c = solvePhaseC(model, q, v, tc, d);
  const int ks = layout::stroke(0);
  Eigen::Matrix2d A;
  A << b.vdot[kTheta] - a.vdot[kTheta], c.vdot[kTheta] - a.vdot[kTheta], b.vdot[ks] - a.vdot[ks],
      c.vdot[ks] - a.vdot[ks];
  const Eigen::Vector2d x = A.lu().solve(Eigen::Vector2d(-a.vdot[kTheta], -a.vdot[ks]));
  StaticForces out;
  out.fn = a.fn + x[0] * (b.fn - a.fn) + x[1] * (c.fn - a.fn);
  out.ft = a.ft + x[0] * (b.ft - a.ft) + x[1] * (c.ft - a.ft);
  out.margin = INFINITY;
  for (int i = 0; i < m; ++i)
    out.margin =
        std::min(out.margin, model.cell().friction.mu_static * out.fn[i] - std::abs(out.ft[i]));
  return out;
}

TEST(SimulatorValidation, HeldPartStartsToSlideAtThePredictedTilt) {
  const RbsfModel model(twoFingerCell());
  const VecQ q0 = restingConfiguration(model, Pose{0.0, 0.40, 0.0}, 0.0);
  // Finger forces: the holding tau, with the difference between the two fingers chosen
  // (coarse scan) to centre the forces in their cones at zero tilt.
  HoldingSolution hold = test::holdingAt(model, q0);
  ASSERT_TRUE(hold.feasible);
  VecU tau0 = hold.tau;
  double best = -INFINITY, best_shift = 0.0;
  for (double shift = -40.0; shift <= 40.0; shift += 2.0) {
    VecU t = tau0;
    t[1] += shift, t[2] -= shift;
    const double margin = staticForces(model, q0, t, 0.0).margin;
    if (margin > best) best = margin, best_shift = shift;
  }
  tau0[1] += best_shift, tau0[2] -= best_shift;
  ASSERT_GT(best, 20.0);
  // Predicted onset: first tilt (tilting clockwise, the base angle decreasing) with a
  // negative margin, refined by bisection.
  double lo = 0.0, hi = 0.0;
  for (double tilt = 0.0; tilt < 0.6; tilt += 0.005) {
    if (staticForces(model, q0, tau0, -tilt).margin < 0.0) {
      hi = tilt;
      break;
    }
    lo = tilt;
  }
  ASSERT_GT(hi, 0.0) << "the part never slips below 0.6 rad";
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (staticForces(model, q0, tau0, -mid).margin < 0.0 ? hi : lo) = mid;
  }
  const double predicted = -0.5 * (lo + hi);
  ASSERT_LT(predicted, -5.0 * M_PI / 180.0);  // a tilt worth measuring

  // Simulation: base ramped at -1 deg/s by its PD (no rate feedforward: no kick at t = 0),
  // strokes held at their start values.
  const Simulator sim(model);
  SimulatorWorkspace ws(2);
  SimState s(q0, VecQ::Zero(6));
  StepReport rep;
  const double rate = -M_PI / 180.0;
  const VecC strokes = test::strokesOf(q0);
  const test::Servo servo;
  double onset = NAN;
  for (int k = 0; k < 30000 && std::isnan(onset); ++k) {
    const double theta = s.q[kTheta];
    sim.step(s, servo(tau0, s, rate * s.t, 0.0, strokes), ws, &rep);
    if (rep.phase != Phase::kC) onset = theta;
    // Until then the part is stuck and the forces are those of the analysis.
    if (std::isnan(onset) && k % 1000 == 999) {
      const StaticForces f = staticForces(model, q0, tau0, s.q[kTheta]);
      for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(rep.contacts[i].f_n, f.fn[i], 0.5) << "t = " << s.t;
        EXPECT_NEAR(rep.contacts[i].f_t, f.ft[i], 0.5) << "t = " << s.t;
      }
    }
  }
  ASSERT_FALSE(std::isnan(onset)) << "no slip within 30 degrees";
  RecordProperty("predicted_slip_tilt_deg", test::figure(predicted * 180.0 / M_PI));
  RecordProperty("simulated_slip_tilt_deg", test::figure(onset * 180.0 / M_PI));
  EXPECT_NEAR(onset, predicted, 0.5 * M_PI / 180.0)
      << "simulated " << onset * 180 / M_PI << " deg, predicted " << predicted * 180 / M_PI;
  EXPECT_TRUE(rep.contacts[0].mode != ContactMode::kStick ||
              rep.contacts[1].mode != ContactMode::kStick);
}

TEST(SimulatorValidation, PhaseUForcesConvergeToTheLcpAsTheStepShrinks) {
  // Frictionless, every contact sliding and held closed by the finger forces. After the same
  // simulated time, the last step's forces are compared with forwardDynamicsU() at the state
  // that step started from. The error must fall at least linearly with h.
  Cell cell = test::makeCell(ShapeKind::kEllipse, 3);
  const RbsfModel holding_model(cell);
  cell.friction = {0.0, 0.0};
  const RbsfModel model(cell);
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.1}, 0.1);
  const HoldingSolution hold = test::holdingAt(holding_model, q0);
  ASSERT_TRUE(hold.feasible);
  VecU tau = hold.tau;
  tau[kTauTheta] -= 5.0, tau[1] += 20.0, tau[3] += 10.0;
  ModelData d(3);
  model.updateContacts(q0, d);
  VecQ v0 = VecQ::Zero(7);
  v0 << 0.1, -0.05, 0.3, 0.2, 0.0, 0.0, 0.0;
  for (int i = 0; i < 3; ++i)
    v0[layout::stroke(i)] = -d.G1.col(i).dot(v0) / d.G1(layout::stroke(i), i);
  auto error = [&](double h) {
    SimulatorSettings settings;
    settings.time_step = h;
    const Simulator sim(model, settings);
    SimulatorWorkspace ws(3);
    SimState s(q0, v0);
    StepReport rep;
    const int steps = static_cast<int>(std::lround(0.02 / h));
    SimState before = s;
    for (int k = 0; k < steps; ++k) {
      before = s;
      sim.step(s, tau, ws, &rep);
    }
    EXPECT_EQ(rep.phase, Phase::kU);
    EXPECT_EQ(rep.touching, 3);
    ModelData lcp(3);
    lcp.xi_hint = before.xi_hint;
    forwardDynamicsU(model, before.q, before.v, tau, lcp);
    double err = 0.0;
    for (int i = 0; i < 3; ++i) {
      EXPECT_GT(lcp.fn[i], 1.0) << "every contact must stay loaded";
      err = std::max(err, std::abs(rep.contacts[i].f_n - lcp.fn[i]));
    }
    return err;
  };
  const double coarse = error(1e-3), fine = error(1e-4);
  RecordProperty("force_error_h1e-3_N", test::figure(coarse));
  RecordProperty("force_error_h1e-4_N", test::figure(fine));
  EXPECT_LT(coarse, 1e-4 * 265.0);  // small against the ~265 N of total load
  // At least linear: ten times smaller for a ten times smaller step.
  EXPECT_LE(fine, 0.1 * coarse) << "coarse " << coarse << " N, fine " << fine << " N";
}

}  // namespace
}  // namespace rbsf
