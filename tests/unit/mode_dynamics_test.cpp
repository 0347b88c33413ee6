// The smooth dynamics of one contact mode (mode_dynamics.h): its accelerations keep the
// mode's constraints, agree with the phase-U LCP where every contact pushes, and its
// linearisation agrees with finite differences (B, F, Lu exactly; the tangent basis spans
// the motions that keep the gaps closed).
#include <gtest/gtest.h>

#include <random>

#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/mode_dynamics.h"
#include "test_support.h"

namespace rbsf {
namespace {

using test::ShapeKind;

ContactModes modesOf(std::initializer_list<ContactMode> list) {
  ContactModes m;
  m.fill(ContactMode::kSeparated);
  int i = 0;
  for (ContactMode c : list) m[i++] = c;
  return m;
}

TEST(ModeDynamics, AccelerationsKeepTheModesConstraints) {
  // Touching contacts: zero normal relative acceleration (eq. 17); sticking ones also zero
  // tangential relative acceleration.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const ModeDynamics dynamics(model);
  std::mt19937 rng(3);
  const int n = model.configDim();
  for (const ContactModes& modes :
       {modesOf({ContactMode::kStick, ContactMode::kStick, ContactMode::kSlide}),
        modesOf({ContactMode::kSlide, ContactMode::kSeparated, ContactMode::kStick}),
        modesOf({ContactMode::kSlide, ContactMode::kSlide, ContactMode::kSlide})}) {
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(n, rng, 0.5);
    const VecU tau = test::randomVector(model.controlDim(), rng, 50.0).head(model.controlDim());
    ModelData data(model.numFingers());
    VecQ vdot;
    dynamics.acceleration(q, v, tau, modes, data, vdot);
    for (int i = 0; i < model.numFingers(); ++i) {
      if (modes[i] == ContactMode::kSeparated) continue;
      EXPECT_NEAR(data.G1.col(i).dot(vdot) + data.h_n[i], 0.0, 1e-6) << "normal " << i;
      if (modes[i] == ContactMode::kStick) {
        EXPECT_NEAR(data.T.col(i).dot(vdot) + data.h_t[i], 0.0, 1e-6) << "tangential " << i;
      }
    }
  }
}

TEST(ModeDynamics, AllSlidingFrictionlessAgreesWithThePhaseULcpWhereEveryContactPushes) {
  // Two independent computations: the mode's equality-constrained solve and the LCP of
  // eqs. 20-24, which agree whenever the LCP closes every contact with a positive force.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const ModeDynamics dynamics(model);
  const ContactModes slide =
      modesOf({ContactMode::kSlide, ContactMode::kSlide, ContactMode::kSlide});
  std::mt19937 rng(5);
  int compared = 0;
  for (int trial = 0; trial < 200 && compared < 10; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(model.configDim(), rng, 0.2);
    VecU tau(model.controlDim());
    tau << 20.0, 150.0, 150.0, 150.0;
    ModelData lcp(model.numFingers());
    forwardDynamicsU(model, q, v, tau, lcp);
    if (!(lcp.fn.minCoeff() > 1.0)) continue;
    ModelData data(model.numFingers());
    VecQ vdot;
    Eigen::VectorXd lambda;
    dynamics.acceleration(q, v, tau, slide, data, vdot, &lambda);
    EXPECT_LT((vdot - lcp.vdot).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + lcp.vdot.norm()));
    EXPECT_LT((lambda - Eigen::VectorXd(lcp.fn)).cwiseAbs().maxCoeff(), 1e-6 * lcp.fn.norm());
    ++compared;
  }
  EXPECT_GE(compared, 5);
}

TEST(ModeDynamics, LinearisationMatchesFiniteDifferences) {
  const RbsfModel model(test::makeCell(ShapeKind::kSuperellipse, 3));
  const ModeDynamics dynamics(model);
  std::mt19937 rng(7);
  const int n = model.configDim(), nu = model.controlDim();
  const ContactModes modes =
      modesOf({ContactMode::kStick, ContactMode::kSlide, ContactMode::kSlide});
  const VecQ q = test::randomContactState(model, rng);
  const VecQ v = test::randomVector(n, rng, 0.3);
  VecU tau(nu);
  tau << 10.0, 120.0, 90.0, 140.0;
  const ModeLinearization lin = dynamics.linearize(q, v, tau, modes);
  ASSERT_EQ(lin.A.rows(), 2 * n);
  EXPECT_LT((lin.A.block(0, n, n, n) - Eigen::MatrixXd::Identity(n, n)).norm(), 1e-15);
  // B, Lu: v' and lambda are affine in tau, so a unit step is exact.
  ModelData data(model.numFingers());
  VecQ base, stepped;
  Eigen::VectorXd l0, l1;
  dynamics.acceleration(q, v, tau, modes, data, base, &l0);
  for (int j = 0; j < nu; ++j) {
    VecU t1 = tau;
    t1[j] += 1.0;
    dynamics.acceleration(q, v, t1, modes, data, stepped, &l1);
    EXPECT_LT((lin.B.block(n, j, n, 1) - (stepped - base)).norm(), 1e-6 * (1 + base.norm()));
    EXPECT_LT((lin.Lu.col(j) - (l1 - l0)).norm(), 1e-6 * (1 + l0.norm()));
  }
  // A's velocity block along a direction, by a one-sided difference of a smaller step.
  const VecQ dv = test::randomVector(n, rng, 1.0);
  dynamics.acceleration(q, v + 1e-5 * dv, tau, modes, data, stepped);
  const Eigen::VectorXd predicted = lin.A.block(n, n, n, n) * Eigen::VectorXd(dv);
  EXPECT_LT((Eigen::VectorXd((stepped - base) / 1e-5) - predicted).norm(),
            1e-3 * (1 + predicted.norm()));
  // Tangent basis: orthonormal, and its position moves keep every touching gap closed to
  // first order.
  EXPECT_LT((lin.tangent.transpose() * lin.tangent -
             Eigen::MatrixXd::Identity(lin.tangent.cols(), lin.tangent.cols()))
                .norm(),
            1e-10);
  model.updateContacts(q, data);
  for (int c = 0; c < lin.tangent.cols(); ++c) {
    const Eigen::VectorXd dq = lin.tangent.col(c).head(n);
    for (int i = 0; i < model.numFingers(); ++i)
      EXPECT_NEAR(data.G1.col(i).dot(dq), 0.0, 1e-8) << "basis " << c << ", contact " << i;
    EXPECT_NEAR(data.T.col(0).dot(dq), 0.0, 1e-8) << "the sticking contact's anchor";
  }
  // Three touching contacts (one sticking: 4 rows) leave 2 x (7 - 4) = 6 directions.
  EXPECT_EQ(lin.tangent.cols(), 6);
}

}  // namespace
}  // namespace rbsf
