// Mass matrix, bias and the acceleration-level LCP of phase U (eqs. 18-24).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "rbsf/dynamics/core/forward_dynamics.h"
#include "test_support.h"

namespace rbsf {
namespace {

using test::ShapeKind;

TEST(MassModel, MassMatrixIsSymmetricPositiveDefiniteAndInvertedExactly) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 4));
  std::mt19937 rng(1);
  const VecQ q = test::randomContactState(model, rng);
  MatQQ M;
  model.massMatrix(q, M);
  EXPECT_LT((M - M.transpose()).norm(), 1e-14);
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(M).info(), Eigen::Success);
  Eigen::MatrixXd X = Eigen::MatrixXd::Random(model.configDim(), 3);
  Eigen::MatrixXd Y = M * X;
  model.applyMassInverse(q, Y);
  EXPECT_LT((Y - X).norm(), 1e-12);
}

TEST(MassModel, BiasIsTheLagrangianOfKineticAndPotentialEnergy) {
  // Q = dM/dt v - 1/2 d(v^T M v)/dq + dV/dq, each term by finite differences.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  std::mt19937 rng(2);
  const int n = model.configDim();
  for (int trial = 0; trial < 5; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(n, rng, 2.0);
    const double eps = 1e-6;
    MatQQ Mp, Mm;
    model.massMatrix(q + eps * v, Mp);
    model.massMatrix(q - eps * v, Mm);
    VecQ expected = (Mp - Mm) / (2 * eps) * v;
    for (int k = 0; k < n; ++k) {
      VecQ qp = q, qm = q;
      qp[k] += eps;
      qm[k] -= eps;
      expected[k] -= (model.kineticEnergy(qp, v) - model.kineticEnergy(qm, v)) / (2 * eps);
      expected[k] += (model.potentialEnergy(qp) - model.potentialEnergy(qm)) / (2 * eps);
    }
    VecQ Q;
    model.bias(q, v, Q);
    EXPECT_LT((Q - expected).norm(), 1e-6 * (1 + Q.norm()));
  }
}

class PhaseUTest : public ::testing::TestWithParam<ShapeKind> {};

TEST_P(PhaseUTest, LcpSolutionIsComplementaryAndSatisfiesTheDynamics) {
  const RbsfModel model(test::makeCell(GetParam(), 3));
  const int m = model.numFingers();
  std::mt19937 rng(4);
  int opened = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(model.configDim(), rng, 0.5);
    VecU tau = test::randomVector(model.controlDim(), rng, 300.0);
    ModelData d(m);
    forwardDynamicsU(model, q, v, tau, d);
    ASSERT_TRUE(d.lcp.solved);
    // Complementarity (eq. 22).
    for (int i = 0; i < m; ++i) {
      EXPECT_GE(d.fn[i], -1e-9);
      EXPECT_GE(d.delta_n[i], -1e-9);
      EXPECT_NEAR(d.fn[i] * d.delta_n[i], 0.0, 1e-7);
      opened += d.fn[i] == 0.0 ? 1 : 0;
    }
    // Eq. 19 and eq. 17 recomputed independently from M, Q and G1.
    MatQQ M;
    model.massMatrix(q, M);
    VecQ Q, u;
    model.bias(q, v, Q);
    model.generalizedInput(tau, u);
    EXPECT_LT((M * d.vdot + Q - u - d.G1 * d.fn).norm(), 1e-8 * (1 + u.norm() + Q.norm()));
    EXPECT_LT((d.G1.transpose() * d.vdot + d.h_n - d.delta_n).norm(), 1e-8);
  }
  EXPECT_GT(opened, 0) << "random torques should open some contacts";
}

TEST_P(PhaseUTest, LcpSolutionIsTheUniqueOneFoundByEnumeration) {
  // With G1 of full column rank the LCP has exactly one solution: enumerate all 2^m
  // active sets and check that exactly one is complementary, and that it is ours.
  const RbsfModel model(test::makeCell(GetParam(), 4));
  const int m = model.numFingers();
  std::mt19937 rng(8);
  for (int trial = 0; trial < 30; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(model.configDim(), rng, 0.5);
    const VecU tau = test::randomVector(model.controlDim(), rng, 300.0);
    ModelData d(m);
    forwardDynamicsU(model, q, v, tau, d);
    EXPECT_GT(smallestSingularValueG1(d), 1e-3);
    const Eigen::MatrixXd A = d.A;
    const Eigen::VectorXd p = d.p;
    int solutions = 0;
    for (int mask = 0; mask < (1 << m); ++mask) {
      std::vector<int> act;
      for (int i = 0; i < m; ++i)
        if (mask & (1 << i)) act.push_back(i);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(m);
      if (!act.empty()) {
        Eigen::MatrixXd Aa(act.size(), act.size());
        Eigen::VectorXd pa(act.size());
        for (size_t a = 0; a < act.size(); ++a) {
          pa[a] = p[act[a]];
          for (size_t b = 0; b < act.size(); ++b) Aa(a, b) = A(act[a], act[b]);
        }
        const Eigen::VectorXd za = Aa.ldlt().solve(-pa);
        for (size_t a = 0; a < act.size(); ++a) z[act[a]] = za[a];
      }
      const Eigen::VectorXd w = A * z + p;
      if (z.minCoeff() >= -1e-9 && w.minCoeff() >= -1e-9) {
        ++solutions;
        EXPECT_LT((z - Eigen::VectorXd(d.fn)).norm(), 1e-7 * (1 + z.norm()));
      }
    }
    EXPECT_EQ(solutions, 1);
  }
}

TEST_P(PhaseUTest, FrictionlessEnergyIsConservedWithContactsHeldAndGravityOff) {
  Cell cell = test::makeCell(GetParam(), 3);
  cell.gravity = 0.0;
  const RbsfModel model(cell);
  const int m = model.numFingers();
  std::mt19937 rng(9);
  VecQ q = test::randomContactState(model, rng);
  // A velocity that keeps every contact closed: project a random one onto G1^T v = 0.
  ModelData d(m);
  model.updateContacts(q, d);
  const Eigen::MatrixXd G1 = d.G1;
  Eigen::VectorXd v0 = Eigen::VectorXd(test::randomVector(model.configDim(), rng, 0.5));
  v0 -= G1 * (G1.transpose() * G1).ldlt().solve(G1.transpose() * v0);
  VecQ v = v0;
  const VecU tau = VecU::Zero(model.controlDim());

  // Contacts held: bilateral normal forces F_n = -A^-1 p (frictionless, so no work).
  auto accel = [&](const VecQ& qq, const VecQ& vv) {
    forwardDynamicsU(model, qq, vv, tau, d);
    const Eigen::VectorXd fn = Eigen::MatrixXd(d.A).ldlt().solve(-Eigen::VectorXd(d.p));
    return VecQ(d.free_acc + d.MinvG1 * fn);
  };
  const double e0 = model.kineticEnergy(q, v);
  ASSERT_GT(e0, 0.01);
  const double h = 2e-4;
  for (int step = 0; step < 5000; ++step) {  // 1 s, classical Runge-Kutta 4
    const VecQ k1v = accel(q, v), k1q = v;
    const VecQ k2v = accel(q + 0.5 * h * k1q, v + 0.5 * h * k1v), k2q = v + 0.5 * h * k1v;
    const VecQ k3v = accel(q + 0.5 * h * k2q, v + 0.5 * h * k2v), k3q = v + 0.5 * h * k2v;
    const VecQ k4v = accel(q + h * k3q, v + h * k3v), k4q = v + h * k3v;
    q += h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  EXPECT_NEAR(model.kineticEnergy(q, v), e0, 1e-6 * e0);
  model.updateContacts(q, d);
  for (int i = 0; i < m; ++i) EXPECT_LT(std::abs(d.contacts[i].gap), 1e-7);
}

INSTANTIATE_TEST_SUITE_P(Shapes, PhaseUTest,
                         ::testing::Values(ShapeKind::kEllipse, ShapeKind::kCircle,
                                           ShapeKind::kSuperellipse));

TEST(Determinacy, DependentNormalsAreDetected) {
  // A disc pinched at its equator by two fingers whose lines are tangent to it: both
  // normals are horizontal and opposite, and G1_1 = -G1_3, so G1 loses column rank.
  Cell cell = test::makeCell(ShapeKind::kCircle, 3);
  const double R = 0.15;
  cell.object.shape = std::make_shared<CircleShape>(R);
  cell.fingers[0].r = -R;
  cell.fingers[1].r = 0.0;
  cell.fingers[2].r = R;
  const RbsfModel model(cell);
  VecQ q = VecQ::Zero(model.configDim());
  q[layout::kY] = 0.40;
  q[layout::stroke(0)] = 0.40;
  q[layout::stroke(1)] = 0.40 - R;
  q[layout::stroke(2)] = 0.40;
  ModelData d(3);
  model.updateContacts(q, d);
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(d.contacts[i].gap), 1e-9);
  EXPECT_LT(smallestSingularValueG1(d), 1e-9);
  // Move the side fingers below the equator: the normals tilt and rank returns.
  const RbsfModel ok(test::makeCell(ShapeKind::kCircle, 3));
  std::mt19937 rng(1);
  ModelData d2(3);
  ok.updateContacts(test::randomContactState(ok, rng), d2);
  EXPECT_GT(smallestSingularValueG1(d2), 1e-2);
}

}  // namespace
}  // namespace rbsf
