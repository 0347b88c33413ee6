// A finger placed after a pivot feels for the part (ContactReading::join_reach): on the
// joints alone the pivot's slip is not seen, so the part may lie higher than planned, and a
// finger that stopped at its planned stroke would be loaded by the hand-over's ramp before
// it touched. The default cell's +5 degree simple turn: finger 1 lifted, a pivot on finger
// 3 with finger 2 sliding, then finger 1 placed and finger 2 lifted at rest.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/planner/support/support_planner.h"
#include "test_support.h"

namespace rbsf::planner {
namespace {

const RbsfModel& defaultModel() {
  static const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  return model;
}

/// The +5 degree simple turn's plan, as plan-reorientation --simple-turns 0.6 makes it.
const plan::Plan& plus5Plan() {
  static const plan::Plan plan = [] {
    SupportPlannerSettings s = test::withoutClock(SupportPlannerSettings{});
    s.simple_turn_friction_uses = {0.6};
    s.friction_uses = {};
    Problem problem;
    problem.start = Pose{0.1, 0.40, 0.0};
    problem.goal = Pose{0.1, 0.40, 5.0 * M_PI / 180};
    SupportPlanner planner(defaultModel(), s);
    plan::Plan p;
    if (!planner.solve(problem, p)) ADD_FAILURE() << planner.message();
    return p;
  }();
  return plan;
}

/// The start of the plan's hand-over ramp onto finger 1: its first stretch with fingers 1
/// and 2 both free (F F S).
double rampStart(const plan::Plan& plan) {
  double t = 0.0;
  for (const plan::PlanSegment& s : plan.segments) {
    if (rolesText(s.contacts, 3) == "FFS") return t;
    t += s.duration;
  }
  return -1.0;
}

TEST(JoiningFinger, OnlyAFingerThatRisesFromLiftedJoinsUntilItIsReliedOn) {
  const plan::Plan& plan = plus5Plan();
  ASSERT_FALSE(plan.segments.empty());
  const FeedbackSchedule schedule(defaultModel(), plan::makeReference(plan),
                                  plan::lawSensing(defaultModel().cell().sensing, plan),
                                  plan.simulator, FeedbackSettings{});
  int joining_knots[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    ContactRole last = ContactRole::kUnplanned;  // the last role other than F
    for (int k = 0; k < schedule.numKnots(); ++k) {
      const ContactRole r = schedule.roles(k)[i];
      const bool joining = (schedule.joining(k) >> i) & 1u;
      EXPECT_EQ(joining, r == ContactRole::kFree && last == ContactRole::kLifted)
          << "finger " << i + 1 << " knot " << k;
      joining_knots[i] += joining ? 1 : 0;
      if (r != ContactRole::kFree) last = r;
    }
  }
  // Finger 1 rises and joins (its approach, the rest at its stroke and the ramp); finger 2
  // leaves (free in the ramp after sticking) and finger 3 never lets go.
  EXPECT_GT(joining_knots[0], 100);
  EXPECT_EQ(joining_knots[1], 0);
  EXPECT_EQ(joining_knots[2], 0);
}

TEST(JoiningFinger, MeetsThePartBeforeTheRampWhereItStopsShortAtItsPlannedStroke) {
  // Certificate trials (the cell's draws, joint feedback): with the law's reach every
  // trial's finger 1 presses the part when the ramp starts; without it, the finger stops at
  // the plan's stroke and in some trials has not touched.
  const plan::Plan& plan = plus5Plan();
  const double ramp = rampStart(plan);
  ASSERT_GT(ramp, 0.0);
  auto untouched = [&](double reach) {
    plan::CertificateSettings s;
    s.feedback.contacts.join_reach = reach;
    int n = 0;
    std::vector<TrajectorySample> trace;
    for (int i = 0; i < 6; ++i) {
      plan::traceTrial(defaultModel(), plan, s, i, trace);
      for (const TrajectorySample& x : trace)
        if (x.t >= ramp) {
          n += x.f_n[0] > 0.0 ? 0 : 1;
          break;
        }
    }
    return n;
  };
  EXPECT_EQ(untouched(FeedbackSettings{}.contacts.join_reach), 0);
  EXPECT_GE(untouched(0.0), 1);
}

}  // namespace
}  // namespace rbsf::planner
