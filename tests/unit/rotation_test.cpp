// Paper section 3: alpha_t, alpha_n, eq. 27 and the three cases of Fig. 3 on the default
// part (ellipse, COM shifted by a third of the semi-major axis, three fingers).
#include <gtest/gtest.h>

#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/rotation_analysis.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "test_support.h"

namespace rbsf {
namespace {

Cell defaultCell() { return loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"); }

struct Fig3Case {
  const char* name;
  Pose pose;
  bool end_pair_encloses;    // COM between the normals of fingers 1 and 3
  bool inner_pair_encloses;  // ... of fingers 1-2 or 2-3
  bool positive, negative;   // expected achievable signs of omega_o'
};

class Fig3Test : public ::testing::TestWithParam<Fig3Case> {};

TEST_P(Fig3Test, SignsOfOmegaDotFollowTheNormalRegions) {
  const Fig3Case& c = GetParam();
  const RbsfModel model(defaultCell());
  const VecQ q = restingConfiguration(model, c.pose, 0.0);
  const VecQ v = VecQ::Zero(model.configDim());
  ModelData d(3);
  model.updateContacts(q, d);
  EXPECT_EQ(comBetweenNormals(d, 0, 2), c.end_pair_encloses);
  EXPECT_EQ(comBetweenNormals(d, 0, 1) || comBetweenNormals(d, 1, 2), c.inner_pair_encloses);

  const OmegaDotRange r = omegaDotRange(model, q, v, d);
  ASSERT_TRUE(r.feasible);
  EXPECT_EQ(r.positive, c.positive);
  EXPECT_EQ(r.negative, c.negative);

  // The extremes are realised: simulate the LP's tau through the LCP (an independent
  // computation), and check eq. 27, I_o omega_o' = -sum(alpha_t f_n), at the same time.
  for (const Eigen::VectorXd& tau : {r.tau_max, r.tau_min}) {
    ModelData e(3);
    forwardDynamicsU(model, q, v, VecU(tau), e);
    double moment = 0.0;
    for (int i = 0; i < 3; ++i) moment -= contactArms(e, i).alpha_t * e.fn[i];
    EXPECT_NEAR(model.cell().object.inertia * e.vdot[layout::kPhi], moment, 1e-6);
    EXPECT_LT((e.G1.transpose() * e.vdot + e.h_n).cwiseAbs().maxCoeff(), 1e-6)
        << "every contact stays closed";
  }
  ModelData e(3);
  forwardDynamicsU(model, q, v, VecU(r.tau_max), e);
  EXPECT_NEAR(e.vdot[layout::kPhi], r.max, 1e-6 * (1 + std::abs(r.max)));
  forwardDynamicsU(model, q, v, VecU(r.tau_min), e);
  EXPECT_NEAR(e.vdot[layout::kPhi], r.min, 1e-6 * (1 + std::abs(r.min)));
}

INSTANTIATE_TEST_SUITE_P(
    PaperFig3, Fig3Test,
    ::testing::Values(
        // (a) COM inside the end fingers' normal region: both signs.
        Fig3Case{"end_fingers", Pose{-0.10, 0.40, -3.10}, true, true, true, true},
        // (b) outside the end fingers' region, inside an inner pair's: still both signs.
        Fig3Case{"inner_pair", Pose{0.05, 0.40, -0.90}, false, true, true, true},
        // (c) outside every region: every alpha_t has one sign, so only one sign.
        Fig3Case{"no_region", Pose{0.15, 0.40, 0.30}, false, false, false, true}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(ContactArms, ReconstructTheContactPoint) {
  // c(xi) = -(alpha_n n + alpha_t t) (eq. 25), for random states of every shape.
  for (auto kind :
       {test::ShapeKind::kEllipse, test::ShapeKind::kCircle, test::ShapeKind::kSuperellipse}) {
    const RbsfModel model(test::makeCell(kind));
    std::mt19937 rng(21);
    ModelData d(3);
    model.updateContacts(test::randomContactState(model, rng), d);
    for (int i = 0; i < 3; ++i) {
      const ContactArms a = contactArms(d, i);
      const ContactFrame& c = d.contacts[i];
      EXPECT_LT((c.lever + a.alpha_n * c.normal + a.alpha_t * c.tangent).norm(), 1e-12);
    }
  }
}

TEST(OmegaDotRange, TighterLimitsNarrowTheRange) {
  // The LP's bounds matter: with weaker fingers the achievable range shrinks.
  Cell weak = defaultCell();
  for (FingerParams& f : weak.fingers) f.force_limit = 300.0;
  const RbsfModel strong_model(defaultCell()), weak_model(weak);
  const Pose pose{-0.10, 0.40, -3.10};
  const VecQ q = restingConfiguration(strong_model, pose, 0.0);
  const VecQ v = VecQ::Zero(7);
  ModelData d(3);
  strong_model.updateContacts(q, d);
  const OmegaDotRange strong = omegaDotRange(strong_model, q, v, d);
  const OmegaDotRange narrow = omegaDotRange(weak_model, q, v, d);
  ASSERT_TRUE(strong.feasible && narrow.feasible);
  EXPECT_LT(narrow.max, strong.max - 1.0);
  EXPECT_GT(narrow.min, strong.min + 1.0);
}

}  // namespace
}  // namespace rbsf
