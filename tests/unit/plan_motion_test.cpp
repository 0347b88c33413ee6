// The plan's motion against the cell's motion limits (plan/plan_motion.h): peaks and
// the final rest measured over the samples, the violation named in metres and degrees,
// and a certificate that refuses a plan outside the limits whatever its trials; and its
// holding (plan_holding.h): a part on two frictionless tips is not held by the joints; and
// its planned phases and pivots, read from the segments' roles.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "law_support.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_holding.h"
#include "rbsf/plan/plan_motion.h"

namespace rbsf::plan {
namespace {

/// A plan with samples at t = 0, 1, 2 whose part velocities are given (m = 3).
Plan samplePlan(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2) {
  Plan plan;
  int k = 0;
  for (const Eigen::Vector3d& v : {v0, v1, v2}) {
    TrajectorySample s;
    s.t = k++;
    s.q = VecQ::Zero(layout::configDim(3));
    s.v = VecQ::Zero(layout::configDim(3));
    s.v[layout::kX] = v[0];
    s.v[layout::kY] = v[1];
    s.v[layout::kPhi] = v[2];
    plan.samples.push_back(s);
  }
  return plan;
}

TEST(PlanMotion, PeaksAndTheFinalRestAreMeasuredOverTheSamples) {
  const MotionLimits limits;
  const PlanMotion m =
      measureMotion(samplePlan(Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(0.3, -0.4, 0.2),
                               Eigen::Vector3d(0.0, 0.0, -1.5)),
                    limits);
  ASSERT_TRUE(m.measured);
  EXPECT_DOUBLE_EQ(m.peak_speed, 0.5);  // |(0.3, -0.4)|
  EXPECT_DOUBLE_EQ(m.peak_speed_time, 1.0);
  EXPECT_DOUBLE_EQ(m.peak_angular_speed, 1.5);  // |phi'|, either sign
  EXPECT_DOUBLE_EQ(m.peak_angular_time, 2.0);
  EXPECT_DOUBLE_EQ(m.end_angular_speed, 1.5);
  EXPECT_FALSE(m.withinLimits());
  EXPECT_FALSE(m.endsAtRest());
  EXPECT_FALSE(m.ok());
  const std::string why = motionViolationText(m);
  EXPECT_NE(why.find("moves the part at 0.5 m/s at t = 1 s (limit 0.25 m/s)"), std::string::npos)
      << why;
  EXPECT_NE(why.find("turns the part at 85.9 deg/s at t = 2 s (limit 57.3 deg/s)"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("ends turning at 85.9 deg/s"), std::string::npos) << why;
}

TEST(PlanMotion, ASlowPlanEndingAtRestIsWithinTheLimitsAndEachBoundIsItsOwn) {
  MotionLimits limits;
  const Plan slow = samplePlan(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.2, 0.1, 0.9),
                               Eigen::Vector3d(5e-4, 0, -5e-4));
  EXPECT_TRUE(measureMotion(slow, limits).ok()) << motionViolationText(measureMotion(slow, limits));
  EXPECT_EQ(motionViolationText(measureMotion(slow, limits)), "");
  limits.rest_speed = 4e-4;  // the last sample moves at 5e-4 m/s
  const PlanMotion m = measureMotion(slow, limits);
  EXPECT_TRUE(m.withinLimits());
  EXPECT_FALSE(m.endsAtRest());
  limits = MotionLimits{};
  limits.angular_speed = 0.8;
  EXPECT_FALSE(measureMotion(slow, limits).withinLimits());
  EXPECT_FALSE(measureMotion(Plan{}, limits).measured);
  EXPECT_FALSE(measureMotion(Plan{}, limits).ok());
}

TEST(PlanMotion, ACertificateRefusesAPlanOutsideTheLimitsWhateverItsTrials) {
  // The two-tip plan ends still sliding (7 mm/s): this cell does not ask for rest.
  Cell cell = test::twoTipsCell();
  cell.motion_limits.rest_speed = cell.motion_limits.rest_angular_speed = 1.0;
  const RbsfModel model(cell);
  const Plan plan = test::twoTipsPlan(model);
  CertificateSettings s;
  s.trials = 4;
  s.required_rate = 0.4;  // within 4 of 4 trials' lower bound (0.47): the limits decide
  const Certificate within = certify(model, plan, s);
  ASSERT_TRUE(within.motion.ok()) << motionViolationText(within.motion);
  EXPECT_EQ(within.certified, within.lower_bound >= s.required_rate);
  Cell strict = model.cell();
  strict.motion_limits.part_speed = 0.5 * within.motion.peak_speed;
  const Certificate outside = certify(RbsfModel(strict), plan, s);
  EXPECT_EQ(outside.successes, within.successes);  // the trials are the same
  EXPECT_FALSE(outside.certified);
  EXPECT_NE(verdictText(outside).find("the plan moves the part at"), std::string::npos)
      << verdictText(outside);
  EXPECT_NE(certificateReportText(outside).find("OUTSIDE THE CELL'S LIMITS"), std::string::npos);
}

TEST(PlanHolding, APartSlidingOnTwoFrictionlessTipsIsNotHeldByTheJointsAndTheJointLawSaysSo) {
  // Two sliding contacts give two rows: the joints do not fix the part.
  const RbsfModel model(test::twoTipsCell());
  const Plan plan = test::twoTipsPlan(model);
  const PlanHolding h = measureHolding(model, plan);
  ASSERT_TRUE(h.measured);
  EXPECT_FALSE(h.ok());
  EXPECT_GT(h.longest_free, 0.5 * plan.duration());
  Cell blind = model.cell();
  blind.sensing.part_pose.present = false;
  CertificateSettings s;
  s.trials = 2;
  const Certificate joint = certify(RbsfModel(blind), plan, s);
  EXPECT_TRUE(joint.holding_required);
  EXPECT_FALSE(joint.certified);
  EXPECT_NE(verdictText(joint).find("the joints alone do not hold the part"), std::string::npos)
      << verdictText(joint);
  // Part feedback may hold what the joints cannot: holding is not asked of it.
  EXPECT_FALSE(certify(model, plan, s).holding_required);
}

TEST(PlannedPhases, PivotsAreTheRunsOfSegmentsThatSlideBesideOneStickingTip) {
  // The roles of a two-pivot turn with rests, hand-overs and a slider whose slip turns: the
  // planned phases merge runs, count P runs as pivots, and do not flicker as the simulated
  // phases do.
  Plan plan;
  for (const char* roles : {"LSS", "LFS", "L-S", "L+S", "L-S", "LFS", "LSS", "FSS", "SLS", "+LS",
                            "+LS", "FFS", "++L", "SSS"}) {
    PlanSegment seg;
    seg.contacts = parseRoles(roles, 3, "roles");
    seg.phase = Phase::kC;
    plan.segments.push_back(seg);
  }
  EXPECT_EQ(plan.plannedPhases(), "CPCPCUC");
  EXPECT_EQ(plan.pivots(), 2);
  EXPECT_EQ(plan.phaseSequence(), "C");
  EXPECT_EQ(Plan{}.pivots(), 0);
}

}  // namespace
}  // namespace rbsf::plan
