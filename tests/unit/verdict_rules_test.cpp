// Each rule of the verdict a user trusts, pinned at its boundary (each of these tests fails
// on a plausible one-line slip in the rule): a trial's position and angle tolerances, the
// certificate's bound against the required rate, the rest limits of a plan's end judged
// apart, and the angle difference on both sides of the seam at +-180 degrees.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "law_support.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/confidence.h"
#include "rbsf/plan/plan_motion.h"

namespace rbsf::plan {
namespace {

constexpr double kDeg = M_PI / 180;

/// The certificate tests' exact cell (no uncertainty): a hold succeeds in every trial.
const RbsfModel& exactModel() {
  static const RbsfModel model = [] {
    Cell cell = test::makeCell(test::ShapeKind::kEllipse, 3);
    cell.uncertainty = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    return RbsfModel(cell);
  }();
  return model;
}

/// Holding the part at rest for 0.5 s, its goal moved by (dx, dphi) from where it rests.
Plan holdWithGoalOff(double dx, double dphi) {
  const RbsfModel& model = exactModel();
  Plan plan = test::holdPlan(model, restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0), 0.5);
  plan.goal.x += dx;
  plan.goal.phi += dphi;
  return plan;
}

/// The one trial of a fixed-count certificate of `plan`.
TrialOutcome oneTrial(const Plan& plan) {
  CertificateSettings s;
  s.trials = 1;
  std::vector<TrialOutcome> outcomes;
  certify(exactModel(), plan, s, &outcomes);
  EXPECT_EQ(outcomes.size(), 1u);
  return outcomes.empty() ? TrialOutcome{} : outcomes.front();
}

TEST(VerdictRules, ATrialEndingOneAndAHalfCentimetresFromTheGoalFailsAndSaysSo) {
  // Within 1 cm (the tolerance) passes; 1.5 cm fails, below both twice the position tolerance
  // (2 cm) and the angle tolerance read as metres (3.5 cm).
  const TrialOutcome near = oneTrial(holdWithGoalOff(0.005, 0.0));
  EXPECT_TRUE(near.success) << near.failure;
  const TrialOutcome off = oneTrial(holdWithGoalOff(0.015, 0.0));
  EXPECT_FALSE(off.success);
  EXPECT_NEAR(off.position_error, 0.015, 1e-3);
  EXPECT_NE(off.failure.find(" m from the goal (> 0.01 m)"), std::string::npos) << off.failure;
  // The angle: 1 degree passes, 3 degrees fails (tolerance 2 degrees).
  EXPECT_TRUE(oneTrial(holdWithGoalOff(0.0, 1.0 * kDeg)).success);
  const TrialOutcome turned = oneTrial(holdWithGoalOff(0.0, 3.0 * kDeg));
  EXPECT_FALSE(turned.success);
  EXPECT_NE(turned.failure.find("deg from the goal angle (> 2 deg)"), std::string::npos)
      << turned.failure;
}

TEST(VerdictRules, ABoundEqualToTheRequiredRateCertifiesAndTheNextNumberUpDoesNot) {
  CertificateSettings s;
  s.trials = 8;
  s.required_rate = clopperPearsonLower(8, 8, s.confidence);
  const Plan plan = holdWithGoalOff(0.0, 0.0);
  const Certificate at = certify(exactModel(), plan, s);
  ASSERT_EQ(at.successes, 8);
  EXPECT_EQ(at.lower_bound, s.required_rate);
  EXPECT_TRUE(at.certified) << verdictText(at);
  s.required_rate = std::nextafter(s.required_rate, 1.0);
  EXPECT_FALSE(certify(exactModel(), plan, s).certified);
}

TEST(VerdictRules, ATrialIsAtRestOnlyWhenBothItsSpeedsAre) {
  // The held part settles but never stops exactly: with either of the cell's rest limits
  // (motion_limits.rest, the one rest rule) below its residual speed, the trial is not at
  // rest.
  const Plan plan = holdWithGoalOff(0.0, 0.0);
  const TrialOutcome held = oneTrial(plan);
  ASSERT_TRUE(held.success) << held.failure;
  ASSERT_GT(held.speed, 0.0);
  ASSERT_GT(held.angular_speed, 0.0);
  ASSERT_LE(held.speed, exactModel().cell().motion_limits.rest_speed);
  ASSERT_LE(held.angular_speed, exactModel().cell().motion_limits.rest_angular_speed);
  for (const bool linear : {true, false}) {
    Cell cell = exactModel().cell();
    MotionLimits& limits = cell.motion_limits;
    (linear ? limits.rest_speed : limits.rest_angular_speed) =
        0.5 * (linear ? held.speed : held.angular_speed);
    CertificateSettings s;
    s.trials = 1;
    std::vector<TrialOutcome> outcomes;
    certify(RbsfModel(cell), plan, s, &outcomes);
    ASSERT_EQ(outcomes.size(), 1u);
    EXPECT_FALSE(outcomes[0].success) << (linear ? "linear" : "angular");
    EXPECT_NE(outcomes[0].failure.find("not at rest"), std::string::npos) << outcomes[0].failure;
  }
}

TEST(VerdictRules, ASequentialCertificateStopsAtTheLookWhoseBoundEqualsTheRequiredRate) {
  // Batches of 8 up to 16: all 8 succeed and their bound is exactly the required rate, so the
  // first look certifies and the second batch never runs.
  CertificateSettings s;
  s.batch = 8;
  s.max_trials = 16;
  s.required_rate = clopperPearsonLower(8, 8, s.confidence);
  const Certificate c = certify(exactModel(), holdWithGoalOff(0.0, 0.0), s);
  EXPECT_TRUE(c.certified) << verdictText(c);
  EXPECT_EQ(c.trials, 8);
}

/// A plan whose last sample moves at `speed` [m/s] and turns at `turn` [rad/s].
Plan endingWith(double speed, double turn) {
  Plan plan;
  TrajectorySample last;
  last.t = 1.0;
  last.q = VecQ::Zero(7);
  last.v = VecQ::Zero(7);
  last.v[layout::kX] = speed;
  last.v[layout::kPhi] = turn;
  plan.samples.push_back(last);
  return plan;
}

TEST(VerdictRules, TheRestLimitsOfAPlansEndAreJudgedEachOnItsOwn) {
  MotionLimits apart;
  apart.rest_speed = 1e-4;          // [m/s]
  apart.rest_angular_speed = 1e-3;  // [rad/s]
  // Turning at half the angular limit (five times the linear one): at rest.
  EXPECT_TRUE(measureMotion(endingWith(0.0, 5e-4), apart).endsAtRest());
  EXPECT_FALSE(measureMotion(endingWith(0.0, 2e-3), apart).endsAtRest());
  MotionLimits swapped;
  swapped.rest_speed = 1e-3;
  swapped.rest_angular_speed = 1e-4;
  // Moving at half the linear limit (five times the angular one): at rest.
  EXPECT_TRUE(measureMotion(endingWith(5e-4, 0.0), swapped).endsAtRest());
  EXPECT_FALSE(measureMotion(endingWith(2e-3, 0.0), swapped).endsAtRest());
}

TEST(VerdictRules, AngleDifferencesWrapOnBothSidesOfTheSeam) {
  EXPECT_NEAR(angleDifference(345 * kDeg, 0.0), -15 * kDeg, 1e-12);
  EXPECT_NEAR(angleDifference(0.0, 345 * kDeg), 15 * kDeg, 1e-12);
  EXPECT_NEAR(angleDifference(170 * kDeg, -170 * kDeg), -20 * kDeg, 1e-12);
  EXPECT_NEAR(angleDifference(-170 * kDeg, 170 * kDeg), 20 * kDeg, 1e-12);
  EXPECT_NEAR(angleDifference(725 * kDeg, 0.0), 5 * kDeg, 1e-12);
  // Half a turn is +180 degrees, from either side: the result lies in (-pi, pi].
  EXPECT_NEAR(angleDifference(M_PI, 0.0), M_PI, 1e-12);
  EXPECT_NEAR(angleDifference(-M_PI, 0.0), M_PI, 1e-12);
}

}  // namespace
}  // namespace rbsf::plan
