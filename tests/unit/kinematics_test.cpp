// Contact kinematics against finite differences: G1 is the gradient of the gap, T the
// tangential slip map, J the fingertip Jacobian, h_n and h_t the velocity products.
#include <gtest/gtest.h>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/model.h"
#include "test_support.h"

namespace rbsf {
namespace {

using test::ShapeKind;

class KinematicsTest : public ::testing::TestWithParam<ShapeKind> {};

/// Object-frame position of fingertip i: P = R(-phi) (p_i - x_o).
Vec2 tipInObject(const RbsfModel& model, const VecQ& q, int i) {
  return rotate(-q[layout::kPhi], model.fingertip(q, i) - Vec2(q[layout::kX], q[layout::kY]));
}

TEST_P(KinematicsTest, G1IsGapGradientAndTIsSlipMap) {
  const RbsfModel model(test::makeCell(GetParam()));
  const int nq = model.configDim();
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    VecQ q = test::randomContactState(model, rng);
    if (trial % 2) q += test::randomVector(nq, rng, 0.01);  // off contact too
    ModelData d(model.numFingers());
    model.updateContacts(q, d);
    for (int k = 0; k < nq; ++k) {
      const double eps = 1e-6;
      VecQ qp = q, qm = q;
      qp[k] += eps;
      qm[k] -= eps;
      ModelData dp(model.numFingers()), dm(model.numFingers());
      model.updateContacts(qp, dp);
      model.updateContacts(qm, dm);
      for (int i = 0; i < model.numFingers(); ++i) {
        const double dgap = (dp.contacts[i].gap - dm.contacts[i].gap) / (2 * eps);
        EXPECT_NEAR(d.G1(k, i), dgap, 1e-6) << "q index " << k << " contact " << i;
        // T_i^T v = -t(xi).dP/dt: the tip's slip over the boundary, object frame (at a
        // contact; off contact T is taken at the boundary point, not the tip).
        if (trial % 2) continue;
        const Vec2 dP = (tipInObject(model, qp, i) - tipInObject(model, qm, i)) / (2 * eps);
        const Vec2 t_obj = rotate(-q[layout::kPhi], d.contacts[i].tangent);
        EXPECT_NEAR(d.T(k, i), -t_obj.dot(dP), 1e-7) << "q index " << k << " contact " << i;
      }
    }
  }
}

TEST_P(KinematicsTest, FingertipJacobianMatchesFiniteDifferences) {
  const RbsfModel model(test::makeCell(GetParam()));
  std::mt19937 rng(3);
  const VecQ q = test::randomContactState(model, rng);
  const double eps = 1e-6;
  for (int i = 0; i < model.numFingers(); ++i) {
    Vec2 d_theta, d_stroke;
    model.fingertipJacobian(q, i, d_theta, d_stroke);
    VecQ qp = q, qm = q;
    qp[layout::kTheta] += eps;
    qm[layout::kTheta] -= eps;
    EXPECT_LT((d_theta - (model.fingertip(qp, i) - model.fingertip(qm, i)) / (2 * eps)).norm(),
              1e-8);
    qp = q;
    qm = q;
    qp[layout::stroke(i)] += eps;
    qm[layout::stroke(i)] -= eps;
    EXPECT_LT((d_stroke - (model.fingertip(qp, i) - model.fingertip(qm, i)) / (2 * eps)).norm(),
              1e-8);
  }
}

TEST_P(KinematicsTest, VelocityProductsMatchFiniteDifferencesAlongTrajectory) {
  // Along q(t) = q0 + t v: d/dt (G1(q)^T v) = v^T Hess(g) v = h_n, d/dt (T(q)^T v) = h_t.
  const RbsfModel model(test::makeCell(GetParam()));
  const int m = model.numFingers();
  std::mt19937 rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(model.configDim(), rng, 1.0);
    ModelData d(m), dp(m), dm(m);
    model.updateContacts(q, d);
    model.velocityProducts(q, v, d);
    const double eps = 1e-6;
    model.updateContacts(q + eps * v, dp);
    model.updateContacts(q - eps * v, dm);
    const VecC hn_fd = (dp.G1.transpose() * v - dm.G1.transpose() * v) / (2 * eps);
    const VecC ht_fd = (dp.T.transpose() * v - dm.T.transpose() * v) / (2 * eps);
    for (int i = 0; i < m; ++i) {
      EXPECT_NEAR(d.h_n[i], hn_fd[i], 1e-5 * (1 + std::abs(hn_fd[i]))) << "trial " << trial;
      EXPECT_NEAR(d.h_t[i], ht_fd[i], 1e-5 * (1 + std::abs(ht_fd[i]))) << "trial " << trial;
    }
    // Second difference of the gap itself (gap(q0) = 0 at a contact state).
    for (int i = 0; i < m; ++i) {
      const double e2 = 1e-4;
      ModelData a(m), b(m);
      model.updateContacts(q + e2 * v, a);
      model.updateContacts(q - e2 * v, b);
      const double g2 = (a.contacts[i].gap - 2 * d.contacts[i].gap + b.contacts[i].gap) / (e2 * e2);
      EXPECT_NEAR(d.h_n[i], g2, 1e-3 * (1 + std::abs(g2)));
    }
  }
}

TEST_P(KinematicsTest, PlacementPutsTipsOnTheUnderside) {
  const RbsfModel model(test::makeCell(GetParam()));
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(model.numFingers());
    model.updateContacts(q, d);
    const Vec2 axis = rotate(q[layout::kTheta], Vec2(0, 1));
    for (int i = 0; i < model.numFingers(); ++i) {
      EXPECT_LT(std::abs(d.contacts[i].gap), 1e-9);
      // The inward normal has a component along the finger: the tip pushes from below.
      EXPECT_GT(d.contacts[i].normal.dot(axis), 0.0);
    }
  }
}

TEST(Placement, RefusesUnreachableStrokeNamingTheFinger) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse));
  const Placement p = placeFingers(model, Pose{0.1, 1.5, 0.0}, 0.0);
  EXPECT_FALSE(p.ok);
  EXPECT_EQ(p.finger, 0);
  EXPECT_NE(p.message.find("finger 1"), std::string::npos);
  EXPECT_NE(p.message.find("stroke"), std::string::npos);
  const Placement miss = placeFingers(model, Pose{2.0, 0.4, 0.0}, 0.0);
  EXPECT_FALSE(miss.ok);
  EXPECT_NE(miss.message.find("misses"), std::string::npos);
  EXPECT_THROW(restingConfiguration(model, Pose{2.0, 0.4, 0.0}, 0.0), InputError);
}

INSTANTIATE_TEST_SUITE_P(Shapes, KinematicsTest,
                         ::testing::Values(ShapeKind::kEllipse, ShapeKind::kCircle,
                                           ShapeKind::kSuperellipse));

}  // namespace
}  // namespace rbsf
