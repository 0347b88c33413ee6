// Phases C and P, the proposition of paper 2.2, static holding and classification.
#include <gtest/gtest.h>

#include <Eigen/SVD>

#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/phase.h"
#include "test_support.h"

namespace rbsf {
namespace {

using test::ShapeKind;

class AnalysisTest : public ::testing::TestWithParam<ShapeKind> {};

TEST_P(AnalysisTest, TwoStickingContactsMakeTheObjectTurnWithTheBase) {
  // Paper 2.2: with every contact closed (G1^T v = 0) and two of them sticking
  // (T_1^T v = T_2^T v = 0), every contact sticks and omega_o = theta'.
  const RbsfModel model(test::makeCell(GetParam(), 4));
  const int m = model.numFingers();
  std::mt19937 rng(12);
  for (int trial = 0; trial < 20; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(m);
    model.updateContacts(q, d);
    const int a = trial % m, b = (a + 1 + (trial / m) % (m - 1)) % m;  // every pair a != b
    Eigen::MatrixXd C(m + 2, model.configDim());
    C.topRows(m) = d.G1.transpose();
    C.row(m) = d.T.col(a).transpose();
    C.row(m + 1) = d.T.col(b).transpose();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
    const int rank = static_cast<int>(svd.rank());
    const Eigen::MatrixXd null = svd.matrixV().rightCols(model.configDim() - rank);
    ASSERT_EQ(null.cols(), 2) << "free motions: base rotation and common stroke";
    for (int k = 0; k < null.cols(); ++k) {
      const Eigen::VectorXd v = null.col(k);
      EXPECT_NEAR(v[layout::kPhi], v[layout::kTheta], 1e-10);
      EXPECT_LT((d.T.transpose() * v).norm(), 1e-10);
    }
  }
}

TEST_P(AnalysisTest, HoldingTorqueBalancesTheObjectInsideTheCones) {
  const RbsfModel model(test::makeCell(GetParam(), 3));
  const int m = model.numFingers();
  const double mu = model.cell().friction.mu_static;
  std::mt19937 rng(13);
  int held = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(m);
    model.updateContacts(q, d);
    const HoldingSolution h = holdingTorques(model, q, d);
    if (!h.feasible) continue;
    ++held;
    // Static balance Q(q, 0) = u + G1 F_n + T F_t, forces in cones, tau in limits.
    VecQ Q, u;
    model.bias(q, VecQ::Zero(model.configDim()), Q);
    model.generalizedInput(h.tau, u);
    EXPECT_LT((u + d.G1 * h.fn + d.T * h.ft - Q).norm(), 1e-8 * Q.norm());
    for (int i = 0; i < m; ++i) {
      EXPECT_GE(h.fn[i], -1e-9);
      EXPECT_LE(std::abs(h.ft[i]), mu * h.fn[i] + 1e-8);
      EXPECT_LE(std::abs(h.tau[layout::fingerForce(i)]),
                model.cell().fingers[i].force_limit + 1e-8);
    }
    // Phase C at the holding tau: feasible, and the object stays at rest.
    const VecQ zero = VecQ::Zero(model.configDim());
    const StickSolution c = solvePhaseC(model, q, zero, h.tau, d);
    EXPECT_TRUE(c.feasible);
    EXPECT_LT(c.vdot.norm(), 1e-7);
    EXPECT_EQ(classifyPhase(model, q, zero, h.tau, d).phase, Phase::kC);
  }
  EXPECT_GE(held, 15) << "a part resting on three fingers near level should be holdable";
}

TEST(Holding, TooWeakFingersCannotHold) {
  Cell cell = test::makeCell(ShapeKind::kEllipse, 3);
  for (FingerParams& f : cell.fingers) f.force_limit = 30.0;  // 24 kg part: needs ~235 N
  const RbsfModel model(cell);
  const VecQ q = restingConfiguration(model, Pose{0.10, 0.40, 0.0}, 0.0);
  ModelData d(3);
  model.updateContacts(q, d);
  EXPECT_FALSE(holdingTorques(model, q, d).feasible);
}

TEST_P(AnalysisTest, PhaseCMovesTheObjectWithTheBase) {
  const RbsfModel model(test::makeCell(GetParam(), 3));
  const int m = model.numFingers();
  std::mt19937 rng(14);
  for (int trial = 0; trial < 20; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(m);
    model.updateContacts(q, d);
    // A sticking velocity: base rotation and a common stroke (null space of [G1 T]^T).
    Eigen::MatrixXd C(2 * m, model.configDim());
    C.topRows(m) = d.G1.transpose();
    C.bottomRows(m) = d.T.transpose();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
    const VecQ v = svd.matrixV().rightCols(2) * Eigen::Vector2d(0.3, -0.2);
    const VecU tau = test::randomVector(model.controlDim(), rng, 200.0);
    const StickSolution s = solvePhaseC(model, q, v, tau, d);
    // Rigid with the base at acceleration level: omega_o' = theta'', no slip, no gap change.
    EXPECT_NEAR(s.vdot[layout::kPhi], s.vdot[layout::kTheta], 1e-8);
    EXPECT_LT((d.G1.transpose() * s.vdot + d.h_n).norm(), 1e-7);
    EXPECT_LT((d.T.transpose() * s.vdot + d.h_t).norm(), 1e-7);
  }
}

TEST_P(AnalysisTest, PivotPhaseHoldsItsContactAndLetsOthersSlide) {
  const RbsfModel model(test::makeCell(GetParam(), 3));
  std::mt19937 rng(15);
  const VecQ q = test::randomContactState(model, rng);
  ModelData d(3);
  model.updateContacts(q, d);
  const VecQ v = VecQ::Zero(model.configDim());
  const VecU tau = test::randomVector(model.controlDim(), rng, 200.0);
  const StickSolution p = solvePhaseP(model, q, v, tau, 1, d);
  model.velocityProducts(q, v, d);
  EXPECT_NEAR(d.G1.col(1).dot(p.vdot) + d.h_n[1], 0.0, 1e-8);
  EXPECT_NEAR(d.T.col(1).dot(p.vdot) + d.h_t[1], 0.0, 1e-8);
  for (int i : {0, 2}) {
    const double delta = d.G1.col(i).dot(p.vdot) + d.h_n[i];
    EXPECT_GE(p.fn[i], -1e-9);
    EXPECT_GE(delta, -1e-8);
    EXPECT_NEAR(p.fn[i] * delta, 0.0, 1e-6);
    EXPECT_EQ(p.ft[i], 0.0);
  }
}

TEST(Classification, SlidingContactsGivePhaseU) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const VecQ q = restingConfiguration(model, Pose{0.10, 0.40, 0.0}, 0.0);
  ModelData d(3);
  model.updateContacts(q, d);
  // The object translates sideways over still fingers: every contact slips.
  VecQ v = VecQ::Zero(model.configDim());
  v[layout::kX] = 0.1;
  const VecU tau = VecU::Zero(model.controlDim());
  const PhaseClassification c = classifyPhase(model, q, v, tau, d);
  EXPECT_EQ(c.sticking, 0);
  EXPECT_EQ(c.phase, Phase::kU);
  // At rest, finger 3 alone pushing hard: keeping a common stroke would need fingers 1
  // and 2, which gravity pulls down, to pull on the part. Not C.
  VecU push = VecU::Zero(model.controlDim());
  push[layout::fingerForce(2)] = 800.0;
  const VecQ rest = VecQ::Zero(model.configDim());
  EXPECT_FALSE(solvePhaseC(model, q, rest, push, d).feasible);
  EXPECT_NE(classifyPhase(model, q, rest, push, d).phase, Phase::kC);
}

INSTANTIATE_TEST_SUITE_P(Shapes, AnalysisTest,
                         ::testing::Values(ShapeKind::kEllipse, ShapeKind::kCircle,
                                           ShapeKind::kSuperellipse));

}  // namespace
}  // namespace rbsf
