// The reorientation planner: small problems solved with fixed seeds, re-simulation of a
// plan reproduces it, same seed same plan, plan files round-trip, bad problems refused.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/planner/kinodynamic/goal.h"
#include "rbsf/planner/kinodynamic/planner_setup.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"
#include "rbsf/planner/kinodynamic/state_space.h"
#include "test_support.h"

namespace rbsf::planner {
using namespace rbsf::plan;  // the plan the planner makes
namespace {

const std::string kDefaultCell = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";

Problem smallProblem() {
  Problem p;
  p.start = {0.1, 0.40, 0.0};
  p.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
  return p;
}

PlannerSettings testSettings(std::uint32_t seed) {
  PlannerSettings s;
  s.seed = seed;
  s = test::withoutClock(s);
  s.max_propagations = 200000;  // the searches below end at the goal well within it
  return s;
}

class PlannerTest : public ::testing::Test {
 protected:
  RbsfModel model{loadCell(kDefaultCell)};
};

TEST_F(PlannerTest, SmallProblemSolvedExactlyAndReproducedByResimulation) {
  ReorientationPlanner planner(model, testSettings(4));
  Plan plan;
  ASSERT_TRUE(planner.solve(smallProblem(), plan));
  ASSERT_EQ(plan.status, plan::PlanStatus::kExact);
  EXPECT_LE(plan.goal_distance, 1.0);
  ASSERT_FALSE(plan.segments.empty());
  // The planner's own tree states equal the re-simulation of its controls.
  EXPECT_LE(plan.path_mismatch, 1e-9);

  // Independent re-simulation: a plain loop over the tau segments from q0 at rest.
  const Simulator sim(model, planner.settings().simulator);
  SimulatorWorkspace ws(model.numFingers());
  SimState state(plan.q0, VecQ::Zero(plan.q0.size()));
  std::vector<VecQ> qs{state.q}, vs{state.v};
  StepReport report;
  int touching_min = model.numFingers();
  for (const PlanSegment& seg : plan.segments) {
    ASSERT_EQ(seg.steps, static_cast<int>(std::lround(seg.duration / plan.simulator.time_step)));
    for (int k = 0; k < seg.steps; ++k) {
      sim.step(state, seg.tau, ws, &report);
      qs.push_back(state.q);
      vs.push_back(state.v);
    }
    // Support as the validity checker defines it: fingertips within touch_distance.
    ModelData data(model.numFingers());
    model.updateContacts(state.q, data);
    int touching = 0;
    for (int i = 0; i < model.numFingers(); ++i) {
      if (data.contacts[i].gap <= planner.settings().validity.touch_distance) ++touching;
      EXPECT_GE(data.contacts[i].gap, -planner.settings().validity.penetration_tolerance);
    }
    touching_min = std::min(touching_min, touching);
    // Every segment end stays valid: limits and support.
    const Cell& c = model.cell();
    EXPECT_GE(state.q[layout::kTheta], c.base.theta_min - 1e-3);
    EXPECT_LE(state.q[layout::kTheta], c.base.theta_max + 1e-3);
    for (int i = 0; i < model.numFingers(); ++i) {
      EXPECT_GE(state.q[layout::stroke(i)], c.fingers[i].stroke_min - 1e-3);
      EXPECT_LE(state.q[layout::stroke(i)], c.fingers[i].stroke_max + 1e-3);
    }
    for (int j = 0; j < seg.tau.size(); ++j) {
      const double limit =
          j == layout::kTauTheta ? c.base.torque_limit : c.fingers[j - 1].force_limit;
      EXPECT_LE(std::abs(seg.tau[j]), limit);
    }
  }
  EXPECT_GE(touching_min, 2);
  ASSERT_GE(plan.samples.size(), 2u);
  for (const PlanSample& s : plan.samples) {
    const long k = std::lround(s.t / plan.simulator.time_step);
    ASSERT_LT(k, static_cast<long>(qs.size()));
    EXPECT_LE((s.q - qs[k]).cwiseAbs().maxCoeff(), 1e-9) << "t = " << s.t;
    EXPECT_LE((s.v - vs[k]).cwiseAbs().maxCoeff(), 1e-9) << "t = " << s.t;
  }
  // The last state reaches the goal pose within the tolerances.
  const Pose goal = smallProblem().goal;
  const VecQ& qf = qs.back();
  EXPECT_LE(std::hypot(qf[layout::kX] - goal.x, qf[layout::kY] - goal.y), 0.01);
  EXPECT_LE(std::abs(qf[layout::kPhi] - goal.phi), 2.0 * M_PI / 180.0 + 1e-12);
}

/// The largest part speed |(x', y')| and angular speed |phi'| of the plan's motion, every
/// simulator step (an independent re-simulation of its segments).
std::pair<double, double> peakSpeeds(const RbsfModel& model, const PlannerSettings& s, Plan plan) {
  const Simulator sim(model, s.simulator);
  double linear = 0.0, angular = 0.0;
  for (const PlanSample& p : simulateSegments(sim, plan.q0, plan.segments, 1)) {
    linear = std::max(linear, std::hypot(p.v[layout::kX], p.v[layout::kY]));
    angular = std::max(angular, std::abs(p.v[layout::kPhi]));
  }
  return {linear, angular};
}

TEST_F(PlannerTest, EveryStateOfAPlanKeepsTheMotionLimits) {
  // A budget in propagations (the same plan on any machine). Every simulator step of the
  // plan found is within the cell's motion limits; the same search without the rule finds
  // a throw, so the rule, not the problem, keeps the plan slow.
  const MotionLimits& limits = model.cell().motion_limits;
  PlannerSettings s = testSettings(4);
  Plan slow;
  ASSERT_TRUE(ReorientationPlanner(model, s).solve(smallProblem(), slow));
  ASSERT_FALSE(slow.segments.empty());
  const auto [linear, angular] = peakSpeeds(model, s, slow);
  EXPECT_LE(linear, limits.part_speed);
  EXPECT_LE(angular, limits.angular_speed);

  s.keep_motion_limits = false;
  Plan fast;
  ASSERT_TRUE(ReorientationPlanner(model, s).solve(smallProblem(), fast));
  const auto [fast_linear, fast_angular] = peakSpeeds(model, s, fast);
  EXPECT_TRUE(fast_linear > limits.part_speed || fast_angular > limits.angular_speed)
      << fast_linear << " m/s, " << fast_angular << " rad/s";
}

TEST_F(PlannerTest, GoalIsReachedOnlyBySupportedStates) {
  // The part at the goal pose with every finger retracted is in the region (distance 0)
  // but falling: the goal's progress figure takes it, yet it is no solution, and the search
  // must not stop on it. The same pose held by the fingers is.
  ReorientationPlanner rp(model, testSettings(1));
  Problem at_goal = smallProblem();
  at_goal.start = at_goal.goal;  // the placement rule puts the fingers on the part there
  const VecQ held = rp.checkProblem(at_goal);
  const PlannerSetup setup = rp.setup(smallProblem());
  const auto si = setup.simple_setup->getSpaceInformation();
  ompl::base::State* state = si->allocState();
  VecQ falling = held;
  for (int i = 0; i < model.numFingers(); ++i)
    falling[layout::stroke(i)] = model.cell().fingers[i].stroke_min;
  setup.space->fromSim(SimState(falling, VecQ::Zero(falling.size())), state);
  double d = -1.0;
  EXPECT_FALSE(setup.goal->isSatisfied(state, &d));
  EXPECT_LE(d, 1e-9);
  EXPECT_LE(setup.goal->bestDistance(), 1e-9);
  EXPECT_FALSE(setup.goal->reached());
  setup.space->fromSim(SimState(held, VecQ::Zero(held.size())), state);
  EXPECT_TRUE(setup.goal->isSatisfied(state, &d));
  EXPECT_TRUE(setup.goal->reached());
  si->freeState(state);
}

TEST_F(PlannerTest, SameSeedSamePlan) {
  Plan a, b;
  {
    ReorientationPlanner planner(model, testSettings(12));
    ASSERT_TRUE(planner.solve(smallProblem(), a));
  }
  {
    ReorientationPlanner planner(model, testSettings(12));
    ASSERT_TRUE(planner.solve(smallProblem(), b));
  }
  ASSERT_EQ(a.status, plan::PlanStatus::kExact);
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (size_t k = 0; k < a.segments.size(); ++k) {
    EXPECT_EQ(a.segments[k].steps, b.segments[k].steps);
    EXPECT_TRUE(a.segments[k].tau == b.segments[k].tau) << "segment " << k;
  }
  EXPECT_EQ(a.propagations, b.propagations);
}

TEST_F(PlannerTest, TheCallsCancelStopsTheSearchAndALoweredOneChangesNothing) {
  // The run context, not the settings: with the flag raised before the search it ends at
  // its first check, without the plan the same seed finds; with the flag lowered the search
  // is the one without a context, propagation for propagation.
  Plan plan;
  ReorientationPlanner free_run(model, testSettings(12));
  ASSERT_TRUE(free_run.solve(smallProblem(), plan));
  ASSERT_EQ(plan.status, plan::PlanStatus::kExact);
  const std::atomic<bool> raised{true}, lowered{false};
  ReorientationPlanner stopped(model, testSettings(12));
  Plan none;
  stopped.solve(smallProblem(), none, SearchContext{&raised, nullptr});
  EXPECT_LT(stopped.propagations(), free_run.propagations());
  EXPECT_NE(none.status, plan::PlanStatus::kExact);
  ReorientationPlanner quiet(model, testSettings(12));
  Plan same;
  ASSERT_TRUE(quiet.solve(smallProblem(), same, SearchContext{&lowered, nullptr}));
  EXPECT_EQ(quiet.propagations(), free_run.propagations());
  EXPECT_EQ(same.segments.size(), plan.segments.size());
}

TEST_F(PlannerTest, PlanFileRoundTrips) {
  ReorientationPlanner planner(model, testSettings(4));
  Plan plan;
  ASSERT_TRUE(planner.solve(smallProblem(), plan));
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_plan.json";
  writePlanJson({plan, {}, {}}, path);
  const Plan back = readPlanJson(path).plan;
  EXPECT_EQ(back.status, plan.status);
  EXPECT_EQ(back.planner, "KPIECE1");
  EXPECT_EQ(back.seed, 4u);
  EXPECT_EQ(back.propagations, plan.propagations);
  EXPECT_TRUE(back.q0 == plan.q0);
  ASSERT_EQ(back.segments.size(), plan.segments.size());
  for (size_t k = 0; k < plan.segments.size(); ++k) {
    EXPECT_EQ(back.segments[k].phase, plan.segments[k].phase);
    EXPECT_EQ(back.segments[k].steps, plan.segments[k].steps);
    EXPECT_TRUE(back.segments[k].tau == plan.segments[k].tau);  // bit-exact doubles
  }
  ASSERT_EQ(back.samples.size(), plan.samples.size());
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    EXPECT_TRUE(back.samples[k].q == plan.samples[k].q);
    EXPECT_TRUE(back.samples[k].f_n == plan.samples[k].f_n);
    EXPECT_EQ(back.samples[k].phase, plan.samples[k].phase);
  }
  // The simulator's settings travel with the plan.
  const SimulatorSettings& a = plan.simulator;
  const SimulatorSettings& b = back.simulator;
  EXPECT_EQ(b.time_step, a.time_step);
  EXPECT_EQ(b.activation_distance, a.activation_distance);
  EXPECT_EQ(b.contact_tolerance, a.contact_tolerance);
  EXPECT_EQ(b.slip_tolerance, a.slip_tolerance);
  EXPECT_EQ(b.regularization, a.regularization);
  EXPECT_EQ(b.curvature_terms, a.curvature_terms);
  EXPECT_EQ(b.drift_correction, a.drift_correction);
  EXPECT_EQ(b.max_mode_iterations, a.max_mode_iterations);
  Plan other = plan;
  other.simulator.contact_tolerance = 2e-6;
  other.simulator.curvature_terms = false;
  other.simulator.max_mode_iterations = 5;
  writePlanJson({other, {}, {}}, path);
  const Plan other_back = readPlanJson(path).plan;
  EXPECT_EQ(other_back.simulator.contact_tolerance, 2e-6);
  EXPECT_FALSE(other_back.simulator.curvature_terms);
  EXPECT_EQ(other_back.simulator.max_mode_iterations, 5);
  // So does the law's feedback: a plan held by the joints alone ignores the part's pose.
  EXPECT_FALSE(back.joint_feedback);
  EXPECT_TRUE(lawSensing(model.cell().sensing, back).part_pose.present);
  other.joint_feedback = true;
  writePlanJson({other, {}, {}}, path);
  const Plan joints_back = readPlanJson(path).plan;
  EXPECT_TRUE(joints_back.joint_feedback);
  EXPECT_FALSE(lawSensing(model.cell().sensing, joints_back).part_pose.present);
  // The loaded segments re-simulate to the same samples.
  std::vector<PlanSegment> segs = back.segments;
  const auto again = simulateSegments(planner.simulator(), back.q0, segs, 10);
  ASSERT_EQ(again.size(), plan.samples.size());
  EXPECT_TRUE(again.back().q == plan.samples.back().q);
}

TEST_F(PlannerTest, MalformedPlanFileIsRefused) {
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_bad.json";
  { std::ofstream(path) << R"({"status": "exact", "planner": "RRT"})"; }
  try {
    readPlanJson(path);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("seed is missing"), std::string::npos) << e.what();
  }
  // A simulator setting out of range is named.
  ReorientationPlanner planner(model, testSettings(4));
  Plan plan;
  ASSERT_TRUE(planner.solve(smallProblem(), plan));
  plan.simulator.slip_tolerance = -1.0;
  writePlanJson({plan, {}, {}}, path);
  try {
    readPlanJson(path);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tolerances"), std::string::npos) << e.what();
  }
}

TEST_F(PlannerTest, UnholdableStartAndUnreachableGoalAreRefused) {
  ReorientationPlanner planner(model, testSettings(1));
  Problem p = smallProblem();
  p.start = {0.1, 2.0, 0.0};  // far above every fingertip
  try {
    planner.checkProblem(p);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot hold the start pose"), std::string::npos)
        << e.what();
  }
  p = smallProblem();
  p.goal = {0.1, 3.0, 0.0};
  try {
    planner.checkProblem(p);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("out of reach: no finger"), std::string::npos) << e.what();
  }
  PlannerSettings bad = testSettings(1);
  bad.planner = static_cast<KinodynamicPlanner>(99);  // not a planner
  EXPECT_THROW(ReorientationPlanner(model, bad), InputError);
  // Names: OMPL's, read back; others are not planners.
  for (KinodynamicPlanner p : kinodynamicPlanners()) EXPECT_EQ(parsePlanner(toString(p)), p);
  EXPECT_FALSE(parsePlanner("PRM").has_value());
  EXPECT_FALSE(parsePlanner("kpiece1").has_value());
}

TEST_F(PlannerTest, UnholdableStartOfAWeakCellIsRefused) {
  Cell cell = loadCell(kDefaultCell);
  for (FingerParams& f : cell.fingers) f.force_limit = 1.0;  // cannot carry 24 kg
  const RbsfModel weak(cell);
  ReorientationPlanner planner(weak, testSettings(1));
  try {
    planner.checkProblem(smallProblem());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot hold the part at rest"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rbsf::planner
