// TrackingController: the default gains follow omega_n and zeta, a perturbed start is
// rejected (closed loop holds the part where open loop loses it), tau saturates at the
// cell's limits, bad settings are refused.
#include <gtest/gtest.h>

#include <cmath>

#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/holding.h"
#include "rbsf/dynamics/simulator.h"
#include "rbsf/dynamics/state_layout.h"
#include "rbsf/dynamics/tracking_controller.h"
#include "test_support.h"

namespace rbsf {
namespace {

class TrackingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
    ModelData d(3);
    model.updateContacts(q0, d);
    const HoldingSolution hold = holdingTorques(model, q0, d);
    ASSERT_TRUE(hold.feasible);
    // Reference: the part held at rest for 2 s with the holding torques.
    ref.addKnot(0.0, q0, VecQ::Zero(7));
    ref.addKnot(2.0, q0, VecQ::Zero(7));
    ref.addInputPiece(0.0, 2.0, VecU(hold.tau), VecU(), Phase::kC);
  }

  /// Largest |theta - theta_ref| over the last second of a 2 s run started with the base
  /// and the part on it turning at 0.005 rad/s.
  double finalError(const TrackingController* controller) {
    const Simulator sim(model);
    SimulatorWorkspace ws(3);
    // The held part turning rigidly with the base about the origin (consistent with
    // sticking contacts, phase C). Much faster starts (0.01 rad/s) set the part slipping on
    // the fingers, and with mu_k = 0 it then slides away whatever the joints do.
    const double w = 0.005;
    VecQ v0 = VecQ::Zero(7);
    v0[layout::kX] = -w * q0[layout::kY];
    v0[layout::kY] = w * q0[layout::kX];
    v0[layout::kPhi] = w;
    v0[layout::kTheta] = w;
    SimState s(q0, v0);
    ReferenceSample r;
    VecU tau;
    double worst = 0.0;
    for (int k = 0; k < 2000; ++k) {
      ref.sample(s.t, r);
      if (controller)
        controller->compute(s.q, s.v, r, tau);
      else
        tau = r.tau;
      sim.step(s, tau, ws);
      if (k >= 1000) worst = std::max(worst, TrackingController::jointError(s.q, r));
    }
    return worst;
  }

  RbsfModel model{test::makeCell(test::ShapeKind::kEllipse, 3)};
  VecQ q0;
  ReferenceTrajectory ref;
};

TEST_F(TrackingTest, DefaultGainsFollowFrequencyAndDamping) {
  TrackingSettings settings;
  settings.natural_frequency = 10.0;
  settings.damping_ratio = 0.7;
  const TrackingController c(model, q0, settings);
  const VecU I = TrackingController::effectiveInertia(model, q0);
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(c.kp()[j], 100.0 * I[j], 1e-9 * I[j]);
    EXPECT_NEAR(c.kd()[j], 14.0 * I[j], 1e-9 * I[j]);
  }
  // Base: M_R[0,0] + the part turning about the origin.
  MatQQ M;
  model.massMatrix(q0, M);
  const double r2 = q0[0] * q0[0] + q0[1] * q0[1];
  EXPECT_NEAR(I[0], M(3, 3) + 0.675 + 24.0 * r2, 1e-12);
  EXPECT_NEAR(I[2], model.cell().fingers[1].mass + 8.0, 1e-12);
}

TEST_F(TrackingTest, RejectsAPerturbedStart) {
  const TrackingController c(model, q0);
  const double open = finalError(nullptr), closed = finalError(&c);
  // Open loop the base is an inverted pendulum: the perturbation grows.
  EXPECT_GT(open, 0.02);
  EXPECT_LT(closed, 1e-3);
  EXPECT_LT(closed, 0.02 * open);
}

TEST_F(TrackingTest, SaturatesAtTheLimits) {
  const TrackingController c(model, q0);
  ReferenceSample r;
  ref.sample(0.0, r);
  VecQ q = q0;
  VecU tau;
  EXPECT_FALSE(c.compute(q, VecQ::Zero(7), r, tau));  // at the reference: tau_ff
  EXPECT_LE((tau - r.tau).cwiseAbs().maxCoeff(), 1e-12);
  q[layout::kTheta] -= 1.0;  // far behind: every joint demands more than its limit
  for (int i = 0; i < 3; ++i) q[layout::stroke(i)] += 1.0;
  EXPECT_TRUE(c.compute(q, VecQ::Zero(7), r, tau));
  EXPECT_EQ(tau[layout::kTauTheta], model.cell().base.torque_limit);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(tau[layout::fingerForce(i)], -model.cell().fingers[i].force_limit);
}

TEST_F(TrackingTest, RefusesBadSettings) {
  TrackingSettings s;
  s.natural_frequency = 0.0;
  EXPECT_THROW(TrackingController(model, q0, s), InputError);
  TrackingController c(model, q0);
  EXPECT_THROW(c.setGains(VecU::Constant(4, -1.0), VecU::Zero(4)), InputError);
  EXPECT_THROW(c.setGains(VecU::Zero(3), VecU::Zero(3)), InputError);
}

}  // namespace
}  // namespace rbsf
