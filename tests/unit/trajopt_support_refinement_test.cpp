// Refining a support plan (plan_refinement.h supportOptimizerSettings): on its stated roles,
// within the margins it was planned with and near its path, the refinement keeps every
// sticking force inside the friction-use cone and runs at least as well as the planner's
// plan on the same draws; the same refinement without those margins drops the part.
#include <gtest/gtest.h>

#include <cmath>

#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_holding.h"
#include "rbsf/planner/pipeline/refine_and_certify.h"
#include "rbsf/planner/support/support_planner.h"
#include "rbsf/trajopt/plan_refinement.h"
#include "rbsf/trajopt/schedule.h"
#include "test_support.h"
#include "trajopt_support.h"

namespace rbsf::trajopt {
namespace {

struct Planned {
  plan::Plan plan;
  plan::PlanMargins margins;
};

// The support planner's -15 degree turn of the default part, on a budget.
const Planned& supportTurn() {
  static const Planned out = [] {
    planner::SupportPlannerSettings s;
    s.max_expansions = 20000;
    s = rbsf::test::withoutClock(s);
    planner::SupportPlanner planner(test::defaultModel(), s);
    planner::Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
    Planned r;
    if (!planner.solve(p, r.plan)) throw std::runtime_error("no support path for -15 degrees");
    r.margins = planner.margins();
    return r;
  }();
  return out;
}

// The simple +5 degree turn (one pivot, then finger 1 placed while it rises to the part).
const Planned& simpleTurn() {
  static const Planned out = [] {
    planner::SupportPlannerSettings s;
    s.simple_turn_friction_uses = {0.6};
    s = rbsf::test::withoutClock(s);
    planner::SupportPlanner planner(test::defaultModel(), s);
    planner::Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = {0.1, 0.40, 5.0 * M_PI / 180.0};
    Planned r;
    if (!planner.solve(p, r.plan)) throw std::runtime_error("no simple turn for +5 degrees");
    r.margins = planner.margins();
    return r;
  }();
  return out;
}

// Bounded by Ipopt's iterations, not the clock (the same result under the sanitizers).
OptimizerSettings base() {
  OptimizerSettings s;
  s.max_solve_time = 3600.0;
  return s;
}

plan::CertificateSettings fewTrials() {
  plan::CertificateSettings c;
  c.trials = 12;  // the same seed: the same draws for every plan certified
  return c;
}

TEST(SupportRefinement, StickingForcesStayInTheFrictionUseConeAndItRunsAtLeastAsWell) {
  const RbsfModel& model = test::defaultModel();
  const Planned& in = supportTurn();
  const OptimizerSettings s = supportOptimizerSettings(base(), in.margins);
  const OptimizedPlan out = PlanOptimizer(model, s).optimize(in.plan);
  ASSERT_TRUE(out.success) << out.summary.message;
  // Every knot's forces against the roles of the interval it starts (the plan's segments
  // are the knot intervals and carry the stated roles).
  const double cone = in.margins.friction_use * model.cell().friction.mu_static;
  const double floor = in.margins.normal_margin * model.cell().object.mass * model.cell().gravity;
  int sticking = 0;
  for (std::size_t k = 0; k < out.plan.samples.size(); ++k) {
    const plan::PlanSegment& seg = out.plan.segments[std::min(k, out.plan.segments.size() - 1)];
    ASSERT_TRUE(planned(seg.contacts));
    for (int i = 0; i < model.numFingers(); ++i) {
      const rbsf::ContactRole r = seg.contacts[i];
      const double fn = out.plan.samples[k].f_n[i], ft = out.f_t[k][i];
      if (r == rbsf::ContactRole::kStick) {
        ++sticking;
        EXPECT_LE(std::abs(ft), cone * fn * (1.0 + 1e-6) + 1e-6) << "knot " << k << " finger " << i;
      }
      if (r == rbsf::ContactRole::kStick || slipSign(r) != 0) {
        EXPECT_GE(fn, floor * (1.0 - 1e-6)) << "knot " << k << " finger " << i;
      }
    }
  }
  EXPECT_GT(sticking, 50);
  // The effort falls, and on the same draws the refinement runs at least as well.
  EXPECT_LT(out.summary.cost_after, 0.8 * out.summary.cost_before);
  const plan::Certificate planned = plan::certify(model, in.plan, fewTrials());
  const plan::Certificate refined = plan::certify(model, out.plan, fewTrials());
  EXPECT_GE(refined.lower_bound, planned.lower_bound)
      << refined.successes << "/" << refined.trials << " against " << planned.successes << "/"
      << planned.trials;
  EXPECT_EQ(refined.successes, refined.trials);
  EXPECT_TRUE(refined.motion.ok());
}

TEST(SupportRefinement, ThePlansEndRestStaysARestAsLongAsPlanned) {
  const RbsfModel& model = test::defaultModel();
  const Planned& in = supportTurn();
  const ScheduleResult sr = buildSchedule(model, in.plan, 100, RunCut::kStatedRoles);
  ASSERT_TRUE(sr.ok()) << sr.error;
  const PhaseRun& rest = sr.schedule.runs.back();
  ASSERT_TRUE(rest.at_rest);  // the planner ends its plans at rest (SupportTiming::end_rest)
  bool moves = false;         // the pivot's run does not rest
  for (const PhaseRun& run : sr.schedule.runs) moves = moves || !run.at_rest;
  EXPECT_TRUE(moves);
  // How long the refined plan's part ends at its final pose (every knot there) [s].
  auto endRest = [&](const plan::Plan& p) {
    const VecQ& end = p.samples.back().q;
    double held = 0.0;
    for (auto s = p.samples.rbegin(); s != p.samples.rend(); ++s) {
      if ((s->q.head<layout::kObjectDim>() - end.head<layout::kObjectDim>()).cwiseAbs().maxCoeff() >
          1e-12)
        break;
      held = p.samples.back().t - s->t;
    }
    return held;
  };
  OptimizerSettings s = supportOptimizerSettings(base(), in.margins);
  const OptimizedPlan kept = PlanOptimizer(model, s).optimize(in.plan);
  ASSERT_TRUE(kept.success) << kept.summary.message;
  // Every knot of the last run is at the goal, over the run's whole planned duration (the
  // collocation then keeps the part's velocities of order h dv/dt there).
  EXPECT_GE(endRest(kept.plan), rest.duration * (1.0 - 1e-9));
  const plan::PlanSample& last = kept.plan.samples.back();
  EXPECT_NEAR(last.q[layout::kX], in.plan.goal.x, 1e-12);
  EXPECT_NEAR(last.q[layout::kY], in.plan.goal.y, 1e-12);
  // Without it the optimiser shortens the rest to brake into the goal.
  s.keep_end_rest = false;
  const OptimizedPlan shortened = PlanOptimizer(model, s).optimize(in.plan);
  ASSERT_TRUE(shortened.success) << shortened.summary.message;
  EXPECT_LT(endRest(shortened.plan), 0.5 * rest.duration);
}

TEST(SupportRefinement, ItsTipsHoldWhereTheirFootPointsStayThoughItsKnotVelocitiesSlip) {
  // The collocation keeps a sticking tip on its material point at every knot, but its knot
  // velocities carry slips of order h dv/dt (up to 6e-4 m/s in the 35 degree refinement).
  // The holding check reads the points as well: knot velocities off by such a slip leave
  // the refined plan held, while the same slip in the positions does not.
  const RbsfModel& model = test::defaultModel();
  const Planned& in = supportTurn();
  const OptimizedPlan out =
      PlanOptimizer(model, supportOptimizerSettings(base(), in.margins)).optimize(in.plan);
  ASSERT_TRUE(out.success) << out.summary.message;
  const plan::HoldingSettings hs;
  ASSERT_TRUE(plan::measureHolding(model, out.plan, hs).ok());
  const double slip = 5.0 * hs.slip_rate;  // [m/s] along the world x
  plan::Plan fast = out.plan, moved = out.plan;
  ModelData data(model.numFingers());
  int read_sliding = 0;
  for (std::size_t k = 0; k < fast.samples.size(); ++k) {
    plan::PlanSample& smp = fast.samples[k];
    smp.v[layout::kX] += slip;
    moved.samples[k].v[layout::kX] += slip;
    moved.samples[k].q[layout::kX] += slip * smp.t;
    model.updateContacts(smp.q, data);
    for (int i = 0; i < model.numFingers(); ++i)
      read_sliding +=
          smp.f_n[i] > hs.touch_force && std::abs(data.T.col(i).dot(smp.v)) > hs.slip_rate;
  }
  ASSERT_GT(read_sliding, 0) << "no velocity reads a slip: the test shows nothing";
  EXPECT_TRUE(plan::measureHolding(model, fast, hs).ok())
      << plan::holdingText(plan::measureHolding(model, fast, hs));
  EXPECT_FALSE(plan::measureHolding(model, moved, hs).ok());
}

TEST(SupportRefinement, AFingerRisingToJoinThePartIsOffWhileItRisesSoTheTurnSolvesInsideTheTube) {
  // A simple turn states F for finger 1 from when it starts to rise until its hand-over; the
  // law raises it until it meets the part, seconds later. Kept on the part for the whole run,
  // the refinement had to touch the part where the planner's finger is 16 cm below it, outside
  // the tube: Ipopt found it infeasible. (Solved, the refinement is certified less well than
  // the planner's plan, which is then written: its hand-over is shortened.)
  const RbsfModel& model = test::defaultModel();
  const Planned& in = simpleTurn();
  const ScheduleResult sr = buildSchedule(model, in.plan, 100, RunCut::kStatedRoles);
  ASSERT_TRUE(sr.ok()) << sr.error;
  int rising = 0;
  for (const PhaseRun& run : sr.schedule.runs)
    for (int i = 0; i < model.numFingers(); ++i)
      rising += run.planned[i] == rbsf::ContactRole::kFree && run.role[i] == ContactRole::kOff;
  EXPECT_GT(rising, 0);
  const OptimizedPlan out =
      PlanOptimizer(model, supportOptimizerSettings(base(), in.margins)).optimize(in.plan);
  EXPECT_TRUE(out.success) << out.summary.message;
  EXPECT_LT(out.summary.cost_after, out.summary.cost_before);
}

TEST(SupportRefinement, WithoutTheMarginsTheSameRefinementDropsThePart) {
  const RbsfModel& model = test::defaultModel();
  const Planned& in = supportTurn();
  // The same roles and optimiser, with none of the margins: the whole cone, no normal
  // floor, no tube around the path, no motion limits.
  OptimizerSettings s = supportOptimizerSettings(base(), in.margins);
  s.cone_margin = 1.0;
  s.normal_floor = 0.0;
  s.tube_position = s.tube_angle = 0.0;
  s.motion_limits = false;
  const OptimizedPlan out = PlanOptimizer(model, s).optimize(in.plan);
  ASSERT_TRUE(out.success) << out.summary.message;
  std::vector<plan::TrialOutcome> trials;
  const plan::Certificate refined = plan::certify(model, out.plan, fewTrials(), &trials);
  int dropped = 0;
  for (const plan::TrialOutcome& t : trials) dropped += t.dropped;
  EXPECT_GE(dropped, refined.trials / 2);
  EXPECT_LT(refined.lower_bound, plan::certify(model, in.plan, fewTrials()).lower_bound);
}

TEST(SupportRefinement,
     ThePipelinesStepWritesTheRefinementOnlyWhenItsCertificateIsAtLeastThePlanners) {
  const RbsfModel& model = test::defaultModel();
  const Planned& in = supportTurn();
  const planner::RefinementResult out =
      planner::refineAndCertify(PlanRefiner(model, base()), in.plan, in.margins, fewTrials());
  ASSERT_TRUE(out.record.certificate.ran);
  EXPECT_EQ(out.refined, planner::atLeastAsGood(out.record.certificate, out.planner_certificate));
  ASSERT_TRUE(out.refined) << out.reason;
  EXPECT_TRUE(out.record.optimization.chosen);
  EXPECT_GE(out.record.certificate.lower_bound, out.planner_certificate.lower_bound);
  for (const plan::PlanSegment& seg : out.record.plan.segments) EXPECT_TRUE(planned(seg.contacts));
}

TEST(SupportRefinement, AtLeastAsGoodComparesTheVerdictThenTheBound) {
  plan::Certificate a, b;
  a.ran = b.ran = true;
  a.lower_bound = b.lower_bound = 0.9;
  EXPECT_TRUE(planner::atLeastAsGood(a, b));  // a tie: at least as good
  b.certified = true;
  EXPECT_FALSE(planner::atLeastAsGood(a, b));  // the planner's certified, the refinement not
  a.certified = true;
  a.lower_bound = 0.9 - 1e-12;
  EXPECT_FALSE(planner::atLeastAsGood(a, b));  // a lower bound below
  a.lower_bound = 0.95;
  EXPECT_TRUE(planner::atLeastAsGood(a, b));
  a.ran = false;
  EXPECT_FALSE(planner::atLeastAsGood(a, b));
}

}  // namespace
}  // namespace rbsf::trajopt
