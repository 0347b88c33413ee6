// The contact forces of a contact set (contact_balance.h): they meet every row of the
// dynamics with the input they return; a balanced sliding support is an equilibrium of the
// phase-U LCP (an independent computation); the margin is the least slack of the forces;
// at breakaway the sliders pull mu_s f_n against their slip; holding at rest agrees with
// holdingTorques(); two frictionless tips, or normals that meet in one point, do not fix the
// part.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <vector>

#include "rbsf/dynamics/core/contact_balance.h"
#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/mode_dynamics.h"
#include "test_support.h"

namespace rbsf {
namespace {

using test::ShapeKind;

constexpr std::uint32_t kAll = 0b111;

/// The default part over three fingers where it slides in balance (COM between the
/// normals): turned 45 deg on the base, the base at 10 deg.
VecQ slidingPose(const RbsfModel& model) {
  const double theta = 10.0 * M_PI / 180;
  const Vec2 x = Eigen::Rotation2Dd(theta) * Vec2(0.10, 0.40);
  return restingConfiguration(model, Pose{x.x(), x.y(), 45.0 * M_PI / 180 + theta}, theta);
}

/// M dv/dt + Q - u - G1 f_n - T f_t over every row.
VecQ residual(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecQ& vdot,
              const ContactBalance& b) {
  ModelData d(model.numFingers());
  model.updateContacts(q, d);
  MatQQ M;
  model.massMatrix(q, M);
  VecQ Q, u;
  model.bias(q, v, Q);
  model.generalizedInput(b.tau, u);
  VecQ r = M * vdot + Q - u;
  for (int i = 0; i < model.numFingers(); ++i) r -= d.G1.col(i) * b.fn[i] + d.T.col(i) * b.ft[i];
  return r;
}

TEST(ContactBalance, ForcesAndInputMeetEveryRowOfTheDynamics) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const ContactBalancer balancer(model);
  std::mt19937 rng(7);
  ModelData data(model.numFingers());
  const VecQ q = slidingPose(model);
  for (const ContactSet set :
       {ContactSet{kAll, 0u}, ContactSet{kAll, 0b100u}, ContactSet{kAll, kAll}}) {
    // A slow motion: the forces stay those of a support, now with every inertial term.
    const VecQ v = test::randomVector(model.configDim(), rng, 0.05);
    const VecQ vdot = test::randomVector(model.configDim(), rng, 0.2);
    const ContactBalance b = balancer.solve(q, v, vdot, set, data);
    ASSERT_TRUE(b.solvable) << "set " << set.touching << "/" << set.sticking;
    EXPECT_LT(residual(model, q, v, vdot, b).cwiseAbs().maxCoeff(), 1e-8);
    for (int i = 0; i < 3; ++i) {
      if (!set.sticks(i)) {
        EXPECT_EQ(b.ft[i], 0.0) << "a sliding contact is frictionless";
      }
      EXPECT_GE(b.fn[i], 0.0);
    }
  }
}

TEST(ContactBalance, ABalancedSlidingSupportIsAnEquilibriumOfThePhaseULcp) {
  // At rest with the returned input, the LCP of eqs. 21-24 (every contact frictionless)
  // gives zero accelerations and the same normal forces.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const ContactBalancer balancer(model);
  const VecQ q = slidingPose(model);
  ModelData data(model.numFingers());
  const ContactBalance b = balancer.statics(q, ContactSet{kAll, 0u}, data);
  ASSERT_TRUE(b.balanced);
  ASSERT_TRUE(b.determined);
  forwardDynamicsU(model, q, VecQ::Zero(q.size()), b.tau, data);
  EXPECT_LT(data.vdot.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((data.fn - b.fn).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(ContactBalance, TheMarginIsTheLeastSlackOfTheForces) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  BalanceSettings s;
  const ContactBalancer balancer(model, s);
  const double W = model.cell().object.mass * model.cell().gravity;
  const VecQ q = slidingPose(model);
  ModelData data(model.numFingers());
  // Three sliding contacts: the forces are unique, the margin is the smallest normal's.
  const ContactBalance u = balancer.statics(q, ContactSet{kAll, 0u}, data);
  EXPECT_NEAR(u.margin, u.fn.minCoeff() / W - s.normal_margin, 1e-9);
  // One sticking: the margin is the least of the normal and cone slacks, and at least what
  // the sliding forces (f_t = 0, a feasible point of the same program) give.
  const ContactBalance p = balancer.statics(q, ContactSet{kAll, 0b010u}, data);
  ASSERT_TRUE(p.solvable);
  std::vector<double> slack;
  for (int i = 0; i < 3; ++i) slack.push_back(p.fn[i] / W - s.normal_margin);
  const double mu = s.friction_use * model.cell().friction.mu_static;
  slack.push_back((mu * p.fn[1] - std::abs(p.ft[1])) / W);
  EXPECT_NEAR(p.margin, *std::min_element(slack.begin(), slack.end()), 1e-9);
  EXPECT_GE(p.margin, std::min(u.margin, mu * u.fn[1] / W) - 1e-9);
}

TEST(ContactBalance, AtBreakawayTheSlidersPullTheStaticLimitAndTheStickersKeepTheirCones) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  BalanceSettings s;
  const ContactBalancer balancer(model, s);
  const VecQ q = slidingPose(model);
  ModelData data(model.numFingers());
  const double mu_s = model.cell().friction.mu_static;
  const double W = model.cell().object.mass * model.cell().gravity;
  const VecQ zero = VecQ::Zero(q.size());
  int solved = 0;
  for (int pivot = 0; pivot < 3; ++pivot) {
    for (const double sign : {-1.0, 1.0}) {
      const ContactSet set{kAll, 1u << pivot};
      VecC slip(3);
      slip << 0.004 * sign, -0.006 * sign, 0.005 * sign;
      slip[pivot] = 0.0;
      const ContactBalance b = balancer.breakaway(q, set, data, slip);
      if (!b.solvable) continue;
      ++solved;
      EXPECT_LT(residual(model, q, zero, zero, b).cwiseAbs().maxCoeff(), 1e-8);
      for (int i = 0; i < 3; ++i) {
        if (i == pivot) {  // inside its cone by the margin (outside when it is negative)
          EXPECT_LE(std::abs(b.ft[i]), s.friction_use * mu_s * b.fn[i] - b.margin * W + 1e-9);
        } else {  // against the slip, at breakaway x mu_s f_n
          EXPECT_NEAR(b.ft[i], -(slip[i] > 0.0 ? 1.0 : -1.0) * s.breakaway * mu_s * b.fn[i], 1e-9);
        }
      }
      // Without the sliders' pull it is the static balance of frictionless slides.
      BalanceSettings none = s;
      none.breakaway = 0.0;
      const ContactBalance free = ContactBalancer(model, none).breakaway(q, set, data, slip);
      const ContactBalance still = balancer.statics(q, set, data);
      EXPECT_NEAR(free.margin, still.margin, 1e-9);
    }
  }
  EXPECT_GE(solved, 3);
  // No planned slip (an empty vector): nothing has to break away.
  const ContactSet pivot{kAll, 0b010u};
  EXPECT_NEAR(balancer.breakaway(q, pivot, data, VecC()).margin,
              balancer.statics(q, pivot, data).margin, 1e-12);
}

TEST(ContactBalance, HoldingAtRestAgreesWithHoldingTorques) {
  // Without margins, every contact sticking, any internal force allowed: balanced exactly
  // when holdingTorques() finds forces in the cones and an input within the limits.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  BalanceSettings s;
  s.normal_margin = 0.0;
  s.friction_use = 1.0;
  s.least_norm = false;
  const ContactBalancer balancer(model, s);
  std::mt19937 rng(11);
  int feasible = 0, infeasible = 0;
  for (int k = 0; k < 40; ++k) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData data(model.numFingers());
    model.updateContacts(q, data);
    const bool hold = holdingTorques(model, q, data).feasible;
    const ContactBalance b = balancer.statics(q, ContactSet{kAll, kAll}, data);
    EXPECT_EQ(b.balanced, hold) << "pose " << k;
    (hold ? feasible : infeasible) += 1;
  }
  EXPECT_GT(feasible, 0);
}

TEST(ContactBalance, TheForcesAreThePlantsForTheirInput) {
  // The balance's forces are the ones the plant's least-norm rule gives its input: the mode
  // dynamics (an independent computation) at that input return the same forces, at rest.
  // Without the rule the three sticking tips' squeeze is chosen freely and differs.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const ModeDynamics dynamics(model);
  ContactModes stick;
  stick.fill(ContactMode::kSeparated);
  for (int i = 0; i < 3; ++i) stick[i] = ContactMode::kStick;
  std::mt19937 rng(5);
  int compared = 0;
  double free_gap = 0.0;
  for (int k = 0; k < 40 && compared < 8; ++k) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData data(3);
    BalanceSettings s;
    s.normal_margin = 0.0;
    s.friction_use = 1.0;
    const ContactBalance b = ContactBalancer(model, s).statics(q, ContactSet{kAll, kAll}, data);
    if (!b.solvable) continue;
    VecQ vdot;
    Eigen::VectorXd lambda;
    dynamics.acceleration(q, VecQ::Zero(7), b.tau, stick, data, vdot, &lambda);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(lambda[i], b.fn[i], 1e-6 * (1.0 + std::abs(b.fn[i]))) << "pose " << k;
      EXPECT_NEAR(lambda[3 + i], b.ft[i], 1e-6 * (1.0 + std::abs(b.fn[i]))) << "pose " << k;
    }
    EXPECT_LT(vdot.norm(), 1e-6) << "at rest, pose " << k;
    s.least_norm = false;
    const ContactBalance f = ContactBalancer(model, s).statics(q, ContactSet{kAll, kAll}, data);
    dynamics.acceleration(q, VecQ::Zero(7), f.tau, stick, data, vdot, &lambda);
    for (int i = 0; i < 3; ++i) free_gap = std::max(free_gap, std::abs(lambda[3 + i] - f.ft[i]));
    ++compared;
  }
  EXPECT_GE(compared, 4);
  EXPECT_GT(free_gap, 1e-3) << "without the rule the LP's squeeze is not the plant's";
}

TEST(ContactBalance, JointsFixThePartOnlyWithThreeIndependentRows) {
  const RbsfModel ellipse(test::makeCell(ShapeKind::kEllipse, 3));
  const ContactBalancer balancer(ellipse);
  ModelData data(3);
  ellipse.updateContacts(slidingPose(ellipse), data);
  EXPECT_TRUE(balancer.determined(ContactSet{kAll, 0u}, data));
  EXPECT_FALSE(balancer.determined(ContactSet{0b011u, 0u}, data)) << "two frictionless tips";
  EXPECT_TRUE(balancer.determined(ContactSet{0b011u, 0b001u}, data)) << "a pivot and a slide";
  // A circle: every normal passes through its centre, so sliding contacts cannot hold its
  // turn however many there are.
  const RbsfModel circle(test::makeCell(ShapeKind::kCircle, 3));
  const ContactBalancer on_circle(circle);
  std::mt19937 rng(3);
  circle.updateContacts(test::randomContactState(circle, rng), data);
  EXPECT_FALSE(on_circle.determined(ContactSet{kAll, 0u}, data));
  EXPECT_TRUE(on_circle.determined(ContactSet{kAll, 0b010u}, data));
}

}  // namespace
}  // namespace rbsf
