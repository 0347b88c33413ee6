// The support planner (support_geometry.h, support_search.h, support_trajectory.h): a pivot
// keeps its tip on one point of the part; a found path is a chain of valid supports, each
// a lattice step or a switch from the last, pivots keeping their anchor and rigid runs
// their pose on the base, ending on the goal; its plan is exact, slow, joint-fed back and
// ends at rest on the goal.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/plan_holding.h"
#include "rbsf/plan/plan_motion.h"
#include "rbsf/planner/support/support_planner.h"
#include "rbsf/planner/support/support_trajectory.h"
#include "support_path_checks.h"
#include "test_support.h"

namespace rbsf::planner {
using namespace rbsf::plan;  // the plan the planner makes
namespace {

const RbsfModel& defaultModel() {
  static const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  return model;
}

/// The search the support planner runs (5 deg and 2 cm steps, greedy).
SupportSearchSettings searchSettings() { return SupportPlannerSettings::defaultSearch(); }

/// The world position of boundary point xi of the part at configuration q.
Vec2 partPoint(const RbsfModel& model, const VecQ& q, double xi) {
  const Vec2 c = model.shape().point(xi);
  const double p = q[layout::kPhi];
  return Vec2(q[layout::kX] + std::cos(p) * c.x() - std::sin(p) * c.y(),
              q[layout::kY] + std::sin(p) * c.x() + std::cos(p) * c.y());
}

const Pose kStart{0.1, 0.40, 0.0};

/// A found path of steps on `set`, each at `start` moved to one (X, theta) of `at`, with its
/// configuration; a waypoint the jig does not reach is left out (callers check the count).
SupportPath pathThrough(SupportGeometry& geometry, const JigPose& start, const ContactSet& set,
                        const std::vector<std::pair<double, double>>& at) {
  SupportPath path;
  path.found = true;
  for (const auto& [X, theta] : at) {
    SupportStep s;
    s.pose = start;
    s.pose.X = X;
    s.pose.theta = theta;
    s.set = set;
    const std::optional<VecQ> q = geometry.configuration(s.pose, set, false);
    if (!q) continue;
    s.q = *q;
    path.steps.push_back(s);
  }
  return path;
}
const Pose kTurn15{0.1, 0.40, -15.0 * M_PI / 180};

TEST(SupportGeometry, WorldAndJigPosesRoundTripAndAPivotKeepsItsTipOnItsPoint) {
  const RbsfModel& model = defaultModel();
  SupportGeometry geometry(model, searchSettings().support);
  const JigPose jp = JigPose::fromWorld(kTurn15, 0.2);
  const Pose back = jp.world();
  EXPECT_NEAR(back.x, kTurn15.x, 1e-12);
  EXPECT_NEAR(back.y, kTurn15.y, 1e-12);
  EXPECT_NEAR(back.phi, kTurn15.phi, 1e-12);

  const JigPose start = JigPose::fromWorld(kStart, 0.0);
  PivotAnchor anchor{2, 0.0, 0.0};
  ASSERT_TRUE(geometry.entry(start, 2, anchor.stroke, anchor.xi));
  const ContactSet pivot{0b111u, 0b100u};
  for (double dpsi : {-0.1, -0.05, 0.05}) {
    for (double theta : {-0.1, 0.0, 0.1}) {
      const JigPose p = geometry.pivotPose(anchor, start.psi + dpsi, theta);
      const std::optional<VecQ> q = geometry.configuration(p, pivot, false);
      ASSERT_TRUE(q.has_value());
      EXPECT_NEAR((*q)[layout::stroke(2)], anchor.stroke, 1e-9);
      EXPECT_LT((model.fingertip(*q, 2) - partPoint(model, *q, anchor.xi)).norm(), 1e-9);
    }
  }
}

TEST(SupportGeometry, ARefusedSupportNamesTheFirstRuleItBreaks) {
  // Each pose breaks one rule, checked against the cell's own numbers: the base beyond its
  // limit, the part lifted above the strokes' reach, the part beside every finger's line,
  // and at the start only forces refuse a set.
  const RbsfModel& model = defaultModel();
  const Cell& cell = model.cell();
  SupportGeometry geometry(model, searchSettings().support);
  const ContactSet all{0b111u, 0b111u};
  SupportRule why = SupportRule::kBlocked;
  JigPose beyond = JigPose::fromWorld(kStart, 0.0);
  beyond.theta = cell.base.theta_max + 0.01;  // the part on the base as at the start
  EXPECT_FALSE(geometry.configuration(beyond, all, true, &why).has_value());
  EXPECT_EQ(why, SupportRule::kBaseLimit);
  EXPECT_TRUE(geometry.configuration(beyond, all, false).has_value());  // only the limit

  JigPose high = JigPose::fromWorld(kStart, 0.0);
  high.Y += cell.fingers[0].stroke_max;  // every tip would have to reach past its stroke
  EXPECT_FALSE(geometry.configuration(high, all, true, &why).has_value());
  EXPECT_EQ(why, SupportRule::kStroke);
  const Support high_support = geometry.check(high, all);
  EXPECT_FALSE(high_support.valid);
  EXPECT_EQ(high_support.refusal, SupportRule::kStroke);

  JigPose aside = JigPose::fromWorld(kStart, 0.0);
  aside.X += 10.0;  // no finger's line meets the part
  EXPECT_FALSE(geometry.configuration(aside, all, true, &why).has_value());
  EXPECT_EQ(why, SupportRule::kReach);

  // At the start every finger's line meets the part within its stroke: a set is refused
  // only by its forces, and some set holds the part.
  int valid = 0;
  for (std::uint32_t touch = 1; touch < 8; ++touch)
    for (std::uint32_t stick = touch;; stick = (stick - 1) & touch) {
      const Support sup = geometry.check(JigPose::fromWorld(kStart, 0.0), ContactSet{touch, stick});
      if (sup.valid)
        ++valid;
      else
        EXPECT_TRUE(sup.refusal == SupportRule::kBalance ||
                    sup.refusal == SupportRule::kUndetermined)
            << touch << " " << stick << " " << supportRuleText(sup.refusal);
      if (stick == 0) break;
    }
  EXPECT_GT(valid, 0);
}

TEST(SupportSearch, ASearchedOutTurnSaysWhatItReachedAndWhatStoppedIt) {
  // Turning the default part over is out of this cell's slow reach (docs/notes): the search
  // ends without a path within a budget, and its reach is consistent with the problem: the
  // start among the angles reached, the closest pose nearer the goal than the start, its
  // distances those of the goal, and the refused moves counted.
  const RbsfModel& model = defaultModel();
  SupportSearchSettings s = searchSettings();
  s.max_expansions = 6000;
  s = test::withoutClock(s);
  SupportSearch search(model, s);
  const Pose over{0.1, 0.40, M_PI};
  const SupportPath path = search.search(kStart, 0.0, over);
  ASSERT_FALSE(path.found);
  const SupportReach& r = path.reach;
  ASSERT_TRUE(r.measured);
  EXPECT_GT(r.poses, 100);
  EXPECT_LE(r.psi_min, 0.0);
  EXPECT_GE(r.psi_max, 0.0);
  EXPECT_LE(r.phi_min, 0.0);
  EXPECT_GE(r.phi_max, 0.0);
  EXPECT_LT(r.psi_max - r.psi_min, 2.0 * M_PI);
  EXPECT_GE(r.closest.phi, r.phi_min - 1e-12);
  EXPECT_LE(r.closest.phi, r.phi_max + 1e-12);
  EXPECT_NEAR(r.closest_position, std::hypot(over.x - r.closest.x, over.y - r.closest.y), 1e-12);
  EXPECT_NEAR(std::abs(r.closest_angle),
              std::abs(std::remainder(over.phi - r.closest.phi, 2 * M_PI)), 1e-12);
  EXPECT_LT(std::abs(r.closest_angle), M_PI - 0.2);  // it got somewhere
  long refused = 0;
  for (long n : r.refused) refused += n;
  EXPECT_GT(refused, 0);
  EXPECT_GT(r.refused[static_cast<int>(r.stoppedBy())], 0);
  EXPECT_EQ(r.refused[static_cast<int>(SupportRule::kBlocked)], 0);  // nothing blocked
  const std::string text = r.text();
  EXPECT_NE(text.find("reached part angles"), std::string::npos) << text;
  EXPECT_NE(text.find(supportRuleText(r.stoppedBy())), std::string::npos) << text;
}

TEST(SupportSearch, APathIsAChainOfValidSupportsEndingOnTheGoal) {
  const RbsfModel& model = defaultModel();
  const SupportSearchSettings s = searchSettings();
  SupportSearch search(model, s);
  const SupportPath path = search.search(kStart, 0.0, kTurn15);
  ASSERT_TRUE(path.found) << path.message;
  SupportGeometry& geometry = search.geometry();
  for (std::size_t k = 0; k < path.steps.size(); ++k) {
    const SupportStep& st = path.steps[k];
    EXPECT_TRUE(geometry.check(st.pose, st.set).valid) << "step " << k;
    if (k == 0) continue;
    const SupportStep& prev = path.steps[k - 1];
    if (st.set != prev.set) {  // a switch happens at rest, in place
      EXPECT_NEAR(st.pose.psi, prev.pose.psi, 1e-12);
      EXPECT_NEAR(st.pose.X, prev.pose.X, 1e-12);
      continue;
    }
    EXPECT_LE(std::abs(st.pose.psi - prev.pose.psi), s.angle_step + 1e-9) << "step " << k;
    EXPECT_LE(std::abs(st.pose.theta - prev.pose.theta), s.angle_step + 1e-9) << "step " << k;
    if (st.set.pivot() >= 0) {  // the pivot's tip stays on its point of the part
      const int f = st.set.pivot();
      EXPECT_EQ(st.anchor.xi, prev.anchor.xi);
      EXPECT_LT((model.fingertip(st.q, f) - partPoint(model, st.q, st.anchor.xi)).norm(), 1e-9);
    } else if (st.set.phase() == Phase::kC) {  // rigid with the base
      EXPECT_NEAR(st.pose.psi, prev.pose.psi, 1e-12);
      EXPECT_NEAR(st.pose.X, prev.pose.X, 1e-12);
    }
  }
  const Pose end = path.steps.back().pose.world();
  EXPECT_NEAR(end.x, kTurn15.x, 1e-9);
  EXPECT_NEAR(end.y, kTurn15.y, 1e-9);
  EXPECT_NEAR(std::remainder(end.phi - kTurn15.phi, 2 * M_PI), 0.0, 1e-9);
}

TEST(SupportTrajectory, ThePlanIsExactSlowJointFedBackAndEndsAtRestOnTheGoal) {
  const RbsfModel& model = defaultModel();
  SupportSearch search(model, searchSettings());
  const SupportPath path = search.search(kStart, 0.0, kTurn15);
  ASSERT_TRUE(path.found);
  const SupportTiming timing;
  const ReferenceTrajectory ref = supportReference(model, search.geometry(), path, timing);
  // The reference respects its speeds (the spline's peak may pass the mean's bound a little).
  ReferenceSample r;
  double speed = 0.0, turn = 0.0;
  for (double t = 0.0; t <= ref.endTime(); t += 0.005) {
    ref.sample(t, r);
    speed = std::max(speed, std::hypot(r.v[layout::kX], r.v[layout::kY]));
    turn = std::max(turn, std::abs(r.v[layout::kPhi]));
  }
  EXPECT_LE(speed, 1.2 * timing.part_speed);
  EXPECT_LE(turn, 1.2 * timing.angular_speed);

  const Plan plan = closedLoopPlan(model, ref, SimulatorSettings{}, FeedbackSettings{}, kTurn15,
                                   0.01, 2.0 * M_PI / 180, 10);
  EXPECT_EQ(plan.status, plan::PlanStatus::kExact);
  EXPECT_TRUE(plan.joint_feedback);
  const PlanSample& last = plan.samples.back();
  EXPECT_LT(std::hypot(last.v[layout::kX], last.v[layout::kY]), 1e-3);
  EXPECT_LT(std::abs(last.v[layout::kPhi]), 1e-3);
  // Exact: its segments re-simulated give its samples bit for bit.
  std::vector<PlanSegment> segments = plan.segments;
  const Simulator sim(model, plan.simulator);
  const std::vector<PlanSample> again = simulateSegments(sim, plan.q0, segments, 10);
  ASSERT_EQ(again.size(), plan.samples.size());
  EXPECT_TRUE(again.back().q == last.q);
  // Handled, not thrown: within the default motion limits at every sample and at rest.
  EXPECT_TRUE(measureMotion(plan, MotionLimits{}).ok())
      << motionViolationText(measureMotion(plan, MotionLimits{}));
  // Held by the joints alone: at every sample the pressed contacts' rows fix the part.
  const PlanHolding held = measureHolding(model, plan);
  EXPECT_TRUE(held.ok()) << holdingText(held);
  EXPECT_LE(held.longest_free, 0.1);

  // The same plan with its contacts released for a while (f_n zeroed): a stretch within
  // the bound passes, a longer one fails and is measured from the last held sample.
  auto released = [&](double from, double to) {
    Plan p = plan;
    for (PlanSample& s : p.samples)
      if (s.t >= from && s.t <= to) s.f_n.setZero();
    return measureHolding(model, p);
  };
  const PlanHolding brief = released(1.0, 1.04);
  EXPECT_TRUE(brief.ok()) << holdingText(brief);
  EXPECT_GT(brief.longest_free, 0.04);
  const PlanHolding long_free = released(1.0, 1.3);
  EXPECT_FALSE(long_free.ok());
  EXPECT_GE(long_free.longest_free, 0.3);
  EXPECT_LT(long_free.longest_free, 0.3 + 0.03);  // samples every 10 steps at most
  EXPECT_LT(long_free.longest_free_start, 1.0);
}

TEST(SupportSearch, EveryRunWithSlidingContactsBreaksAwayWhereItStarts) {
  const RbsfModel& model = defaultModel();
  SupportSearchSettings wide = searchSettings();
  wide.support.balance.friction_use = 0.6;
  const Pose turn45{0.1, 0.40, -45.0 * M_PI / 180};
  for (const Pose& goal : {kTurn15, Pose{0.1, 0.40, -30.0 * M_PI / 180}, turn45}) {
    SupportSearch search(model, goal.phi == turn45.phi ? wide : searchSettings());
    const SupportPath path = search.search(kStart, 0.0, goal);
    ASSERT_TRUE(path.found);
    EXPECT_TRUE(runStartsThatStayStuck(search.geometry(), path).empty()) << goal.phi;
  }
  // Not a vacuous check: without it, the 60 degree turn's path pivots about a lightly loaded
  // tip beside a heavily loaded slider that cannot break loose first, and the 45 degree
  // turn's path has a run on three sliding tips that cannot all break loose at once.
  auto ruleless = [](SupportSearchSettings settings) {
    settings.support.require_breakaway = false;
    return settings;
  };
  {
    SupportSearch search(model, ruleless(searchSettings()));
    const SupportPath path = search.search(kStart, 0.0, Pose{0.1, 0.40, -60.0 * M_PI / 180});
    ASSERT_TRUE(path.found);
    EXPECT_FALSE(runStartsThatStayStuck(search.geometry(), path).empty());
  }
  SupportSearch search(model, ruleless(wide));
  const SupportPath path = search.search(kStart, 0.0, turn45);
  ASSERT_TRUE(path.found);
  const std::vector<SupportStep> stuck = runStartsThatStayStuck(search.geometry(), path);
  EXPECT_TRUE(std::any_of(stuck.begin(), stuck.end(), [](const SupportStep& s) {
    return s.set.sticking == 0;
  })) << "no run on sliding tips alone that cannot start";
}

TEST(SupportSearch, ABlockedCellIsAvoidedByTheNextSearch) {
  const RbsfModel& model = defaultModel();
  SupportSearchSettings s = searchSettings();
  s.time_limit = 10.0;
  SupportSearch search(model, s);
  const SupportPath first = search.search(kStart, 0.0, kTurn15);
  ASSERT_TRUE(first.found) << first.message;
  ASSERT_GT(first.steps.size(), 2u);
  auto cell = [&](const SupportStep& st) {
    return std::array<long, 5>{
        std::lround(st.pose.psi / s.angle_step), std::lround(st.pose.theta / s.angle_step),
        std::lround(st.pose.X / s.xy_step), static_cast<long>(st.set.touching),
        static_cast<long>(st.set.sticking)};
  };
  const SupportStep& middle = first.steps[first.steps.size() / 2];
  search.block(middle);
  EXPECT_EQ(search.blockedCount(), 1u);
  const SupportPath second = search.search(kStart, 0.0, kTurn15);
  ASSERT_TRUE(second.found) << second.message;  // the lattice has other ways round
  bool differs = second.steps.size() != first.steps.size();
  for (std::size_t k = 0; k < second.steps.size(); ++k) {
    EXPECT_NE(cell(second.steps[k]), cell(middle)) << "step " << k << " is in the blocked cell";
    differs = differs || cell(second.steps[k]) != cell(first.steps[k]);
  }
  EXPECT_TRUE(differs);
}

TEST(SupportTrajectory, TheDepartureIsTheFirstSampleOffTheReference) {
  const RbsfModel& model = defaultModel();
  SupportSearch search(model, searchSettings());
  const SupportPath path = search.search(kStart, 0.0, kTurn15);
  ASSERT_TRUE(path.found);
  std::vector<SupportRun> runs;
  const ReferenceTrajectory ref = supportReference(model, search.geometry(), path, {}, &runs);
  // The stretches tile the reference and name the path's steps in order.
  ASSERT_FALSE(runs.empty());
  EXPECT_NEAR(runs.front().start, ref.startTime(), 1e-12);
  EXPECT_NEAR(runs.back().end, ref.endTime(), 1e-9);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    EXPECT_LE(runs[k].first_step, runs[k].last_step);
    EXPECT_LT(runs[k].last_step, path.steps.size());
    if (k > 0) {
      EXPECT_NEAR(runs[k].start, runs[k - 1].end, 1e-9);
    }
    if (!runs[k].handover) {
      EXPECT_EQ(runs[k].set, path.steps[runs[k].first_step].set);
    }
  }
  Plan plan = closedLoopPlan(model, ref, SimulatorSettings{}, FeedbackSettings{}, kTurn15, 0.01,
                             2.0 * M_PI / 180, 10);
  EXPECT_LT(departureTime(plan, ref, 0.005, 0.017), 0.0);  // it follows its reference
  // Turned 1.2 deg off from the middle sample on: it departs there, by angle alone.
  const std::size_t mid = plan.samples.size() / 2;
  for (std::size_t k = mid; k < plan.samples.size(); ++k)
    plan.samples[k].q[layout::kPhi] += 1.2 * M_PI / 180;
  EXPECT_DOUBLE_EQ(departureTime(plan, ref, 0.005, 1.0 * M_PI / 180), plan.samples[mid].t);
  EXPECT_LT(departureTime(plan, ref, 0.005, 1.5 * M_PI / 180), 0.0);
}

// A run's spline through valid waypoints can leave the jig at a corner (Catmull-Rom
// overshoots by 4/27 of half the step before it); the reference then rests at the waypoints
// around that interval and goes straight across it.
TEST(SupportTrajectory, ARunWhoseSplineLeavesTheJigRestsAroundTheIntervalInstead) {
  const RbsfModel& model = defaultModel();
  SupportSearch search(model, searchSettings());
  SupportGeometry& geometry = search.geometry();
  const ContactSet slide{0b111u, 0u};
  const JigPose start = JigPose::fromWorld(kStart, 0.0);
  auto reaches = [&](double X) {
    JigPose p = start;
    p.X = X;
    return geometry.configuration(p, slide, false).has_value();
  };
  ASSERT_TRUE(reaches(start.X));
  // The edge X* of the sliding set's reach, moving the part along the base's X axis.
  double lo = start.X, hi = start.X;
  while (reaches(hi) && hi < start.X + 1.0) hi += 0.005;
  ASSERT_FALSE(reaches(hi));
  for (int k = 0; k < 60; ++k) (reaches(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  // Waypoints: a 2 cm step to 0.5 mm inside the edge, then two base turns there. The spline
  // overshoots X by 0.074 x 2 cm = 1.5 mm in the second interval.
  const double edge = lo, inside = edge - 0.0005, step = 0.02;
  ASSERT_TRUE(reaches(inside - step));
  const SupportPath path =
      pathThrough(geometry, start, slide,
                  {{inside - step, 0.0}, {inside, 0.0}, {inside, 0.05}, {inside, 0.10}});
  ASSERT_EQ(path.steps.size(), 4u);
  std::vector<SupportRun> runs;
  const ReferenceTrajectory ref = supportReference(model, geometry, path, {}, &runs);
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (const SupportRun& r : runs)
    if (!r.handover) spans.emplace_back(r.first_step, r.last_step);
  const std::vector<std::pair<std::size_t, std::size_t>> expected{{0, 1}, {1, 2}, {2, 3}};
  EXPECT_EQ(spans, expected);
  ReferenceSample r;
  for (const SupportRun& run : runs) {  // at rest where the runs meet
    ref.sample(run.end, r);
    EXPECT_LT(r.v.norm(), 1e-6) << "at t = " << run.end;
  }
  for (double t = ref.startTime(); t <= ref.endTime(); t += 0.005) {  // inside the reach
    ref.sample(t, r);
    const Pose w{r.q[layout::kX], r.q[layout::kY], r.q[layout::kPhi]};
    EXPECT_LE(JigPose::fromWorld(w, r.q[layout::kTheta]).X, edge + 1e-9) << "at t = " << t;
  }
}

TEST(SupportTrajectory, ARunEndingOnATinyLastStepApproachesItsEndWithoutTurningBack) {
  // A simple turn's finish can end a run with a step of a thousandth of a lattice step. The
  // uniform spline gives that interval the time of a whole one and, with the tangent of the
  // step before, bends past the end and back: a slider's slip reverses. The run's base angle
  // must rise monotonically to its end, within its waypoints.
  const RbsfModel& model = defaultModel();
  SupportSearch search(model, searchSettings());
  SupportGeometry& geometry = search.geometry();
  const ContactSet held{0b111u, 0b111u};
  const JigPose start = JigPose::fromWorld(kStart, 0.0);
  const double end = 0.10 + 1e-4;
  const SupportPath path = pathThrough(
      geometry, start, held, {{start.X, 0.0}, {start.X, 0.05}, {start.X, 0.10}, {start.X, end}});
  ASSERT_EQ(path.steps.size(), 4u) << "every waypoint on the jig";
  const ReferenceTrajectory ref = supportReference(model, geometry, path, {});
  ReferenceSample r;
  double last = -1.0;
  for (double t = ref.startTime(); t <= ref.endTime(); t += 0.002) {
    ref.sample(t, r);
    EXPECT_GE(r.q[layout::kTheta], last - 1e-7) << "turns back at t = " << t;
    EXPECT_LE(r.q[layout::kTheta], end + 1e-7) << "past the end at t = " << t;
    last = r.q[layout::kTheta];
  }
  ref.sample(ref.endTime(), r);
  EXPECT_NEAR(r.q[layout::kTheta], end, 1e-7) << "the run ends on the last step";
}

TEST(SupportPlanner, PathsWhoseRunsMissTheGoalAreBlockedAndTheLongestRunningIsKept) {
  // A goal tolerance no run can keep: every path found is run, a stretch of it blocked and
  // the search repeated, max_paths times; the plan kept is approximate.
  const RbsfModel& model = defaultModel();
  SupportPlannerSettings s;
  s.friction_uses = {0.45};
  s.time_limit = 20.0;
  s.max_paths = 3;
  Problem problem;
  problem.start = kStart;
  problem.goal = kTurn15;
  problem.tolerance.position = 1e-12;
  SupportPlanner planner(model, s);
  Plan plan;
  ASSERT_TRUE(planner.solve(problem, plan)) << planner.message();
  EXPECT_EQ(planner.pathsRun(), 3);
  EXPECT_EQ(plan.status, plan::PlanStatus::kApproximate);
  EXPECT_EQ(plan.planner, "support");
  // With the default tolerance the first path runs and is kept, exact.
  problem.tolerance = GoalTolerance{};
  SupportPlanner defaults(model, SupportPlannerSettings{});
  ASSERT_TRUE(defaults.solve(problem, plan)) << defaults.message();
  EXPECT_EQ(defaults.pathsRun(), 1);
  EXPECT_EQ(plan.status, plan::PlanStatus::kExact);
}

TEST(SupportPlanner, ARaisedCancelEndsTheSolveBeforeAnySearch) {
  // The call's cancel flag (not a setting): raised, no search expands a node and no plan is
  // made; the same planner with the flag lowered finds the 15 degree plan (the test above).
  const RbsfModel& model = defaultModel();
  Problem problem;
  problem.start = kStart;
  problem.goal = kTurn15;
  SupportPlanner planner(model, SupportPlannerSettings{});
  const std::atomic<bool> raised{true}, lowered{false};
  Plan plan;
  EXPECT_FALSE(planner.solve(problem, plan, &raised));
  EXPECT_EQ(planner.message(), "cancelled");
  EXPECT_EQ(planner.expansions(), 0);
  EXPECT_EQ(planner.pathsRun(), 0);
  EXPECT_TRUE(plan.segments.empty());
  ASSERT_TRUE(planner.solve(problem, plan, &lowered)) << planner.message();
  EXPECT_EQ(plan.status, plan::PlanStatus::kExact);
}

}  // namespace
}  // namespace rbsf::planner
