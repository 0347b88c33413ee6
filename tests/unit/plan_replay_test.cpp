// Plan replay and acceptance on a real planner plan (the planner tests' 15 deg turn, seed
// 7): open loop repeats the planner's own simulation, closed loop ends within tolerance,
// the verdict flips when the goal moves; phase-run filtering.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "rbsf/dynamics/cell.h"
#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/state_layout.h"
#include "rbsf/planner/goal.h"
#include "rbsf/planner/plan_replay.h"
#include "rbsf/planner/reorientation_planner.h"

namespace rbsf::planner {
namespace {

class PlanReplayTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = new RbsfModel(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
    PlannerSettings s;
    s.seed = 7;
    s.time_limit = 120.0;
    // A sample every step: the reference's knots are then the simulated states, so a
    // replay on the plan sees no tracking error. (With the default 10 ms samples the cubic
    // between knots is ~0.3 mm off the path; the PD reacting to that is enough to tip this
    // plan, whose sliding phases end within 0.5 mm of the 1 cm tolerance, either way.)
    s.sample_steps = 1;
    planner_ = new ReorientationPlanner(*model_, s);
    plan_ = new Plan;
    Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
    solved_ = planner_->solve(p, *plan_) && plan_->status == "exact";
  }
  static void TearDownTestSuite() {
    delete plan_;
    delete planner_;
    delete model_;
  }
  void SetUp() override { ASSERT_TRUE(solved_); }

  static RbsfModel* model_;
  static ReorientationPlanner* planner_;
  static Plan* plan_;
  static bool solved_;
};
RbsfModel* PlanReplayTest::model_ = nullptr;
ReorientationPlanner* PlanReplayTest::planner_ = nullptr;
Plan* PlanReplayTest::plan_ = nullptr;
bool PlanReplayTest::solved_ = false;

TEST_F(PlanReplayTest, OpenLoopRepeatsThePlannersSimulation) {
  const ReplayResult r = replayPlan(planner_->simulator(), *plan_, nullptr, {});
  const PlanSample& last = plan_->samples.back();
  ASSERT_NEAR(last.t, plan_->duration(), 1e-9);
  EXPECT_EQ(r.position_error,
            std::hypot(last.q[layout::kX] - plan_->goal.x, last.q[layout::kY] - plan_->goal.y));
  EXPECT_NEAR(r.angle_error, std::abs(angleDifference(last.q[layout::kPhi], plan_->goal.phi)),
              1e-12);
  EXPECT_GE(r.min_f_n, 0.0);
  // The reference passes through the samples, which are the same simulation.
  EXPECT_LE(r.max_tracking_error, 1e-9);
  EXPECT_EQ(r.phases, plannedPhases(*plan_, ReplaySettings{}.min_phase_run));
  EXPECT_LT(r.departure_time, 0.0);  // the plan's own path, throughout
  EXPECT_TRUE(r.departure_phase.empty());
}

TEST_F(PlanReplayTest, DepartureIsWhereThePartFirstLeavesThePlannedPath) {
  // The plan's torques from segment k on are dropped: up to t_k the replay is the
  // planner's own simulation (bit for bit), after it the part falls. The departure must
  // lie after t_k, carry the planned phase there, grow with the tolerances, and be named
  // in the verdict.
  const std::size_t k = plan_->segments.size() / 2;
  double t_k = 0.0;
  for (std::size_t s = 0; s < k; ++s) t_k += plan_->segments[s].duration;
  Plan dropped = *plan_;
  for (std::size_t s = k; s < dropped.segments.size(); ++s) dropped.segments[s].tau.setZero();
  const ReplayResult r = replayPlan(planner_->simulator(), dropped, nullptr, {});
  ASSERT_GE(r.departure_time, 0.0);
  EXPECT_GE(r.departure_time, t_k - 1e-9);
  EXPECT_LE(r.departure_time, dropped.duration() + 1e-9);
  double end = 0.0;
  std::size_t at = 0;
  for (; at + 1 < dropped.segments.size(); ++at) {
    end += dropped.segments[at].duration;
    if (r.departure_time + 0.5 * dropped.simulator.time_step < end) break;
  }
  EXPECT_EQ(r.departure_phase, std::string(1, toString(dropped.segments[at].phase)[0]));
  ReplaySettings loose;
  loose.position_tolerance *= 5.0;
  loose.angle_tolerance *= 5.0;
  const ReplayResult later = replayPlan(planner_->simulator(), dropped, nullptr, loose);
  EXPECT_GT(later.departure_time, r.departure_time);
  std::string reason;
  EXPECT_FALSE(acceptReplay(dropped, r, {}, &reason));
  EXPECT_NE(reason.find("leaves the planned path at t = "), std::string::npos) << reason;
}

TEST_F(PlanReplayTest, ReplayLabelsSegmentsByTheRuleThePlannerLabelsThemBy) {
  // With no run dropped (min_run 0) every segment's label counts: the replay's majority
  // vote per segment must give back exactly the planner's labels, blips inside a segment
  // included. (Comparing per-step runs with per-segment labels rejected the planner's own
  // 30 deg plan, seed 1, for phases PUPCUPUCPU != planned PUPUPCUPUCPU.)
  int mixed = 0;  // segments whose steps were not all of one phase
  {
    SimState state(plan_->q0, VecQ::Zero(plan_->q0.size()));
    SimulatorWorkspace ws(model_->numFingers());
    StepReport report;
    for (const PlanSegment& seg : plan_->segments) {
      std::set<Phase> seen;
      for (int k = 0; k < seg.steps; ++k) {
        planner_->simulator().step(state, seg.tau, ws, &report);
        seen.insert(report.phase == Phase::kUnsupported ? Phase::kU : report.phase);
      }
      mixed += seen.size() > 1;
    }
  }
  EXPECT_GT(mixed, 0) << "the plan no longer exercises mixed segments";
  const ReplayResult r = replayPlan(planner_->simulator(), *plan_, nullptr, {});
  ReplaySettings all;
  all.min_phase_run = 0.0;
  const ReplayResult every = replayPlan(planner_->simulator(), *plan_, nullptr, all);
  EXPECT_EQ(every.phases, plannedPhases(*plan_, 0.0));
  EXPECT_EQ(r.phases, plannedPhases(*plan_, ReplaySettings{}.min_phase_run));
}

TEST_F(PlanReplayTest, ClosedLoopEndsWithinToleranceAndIsAccepted) {
  std::string reason;
  const ReplaySummary s = verifyPlan(planner_->simulator(), *plan_, {}, &reason);
  EXPECT_TRUE(s.ran);
  EXPECT_LE(s.closed_loop.position_error, 0.01);
  EXPECT_LE(s.closed_loop.angle_error, 2.0 * M_PI / 180.0);
  EXPECT_LE(s.closed_loop.max_tracking_error, 0.01);
  EXPECT_TRUE(s.accepted) << reason;
}

TEST_F(PlanReplayTest, VerdictFlipsWhenTheGoalMoves) {
  const TrackingController controller(*model_, plan_->q0);
  Plan moved = *plan_;
  ReplayResult r = replayPlan(planner_->simulator(), moved, &controller, {});
  ASSERT_TRUE(acceptReplay(moved, r, {}));
  moved.goal.x += 0.03;
  r = replayPlan(planner_->simulator(), moved, &controller, {});
  std::string reason;
  EXPECT_FALSE(acceptReplay(moved, r, {}, &reason));
  EXPECT_NE(reason.find("position error"), std::string::npos) << reason;
  moved = *plan_;
  moved.goal.phi += 5.0 * M_PI / 180.0;
  r = replayPlan(planner_->simulator(), moved, &controller, {});
  EXPECT_FALSE(acceptReplay(moved, r, {}, &reason));
  EXPECT_NE(reason.find("angle error"), std::string::npos) << reason;
  // A planned phase sequence the replay does not show is rejected too.
  moved = *plan_;
  for (PlanSegment& seg : moved.segments) seg.phase = Phase::kP;
  EXPECT_FALSE(acceptReplay(moved, r, {}, &reason));
  EXPECT_NE(reason.find("phases"), std::string::npos) << reason;
}

TEST_F(PlanReplayTest, APartBroughtToRestMayEndInOneSettlingRunWithMoreSticking) {
  const TrackingController controller(*model_, plan_->q0);
  Plan p = *plan_;
  ReplayResult r = replayPlan(planner_->simulator(), p, &controller, {});
  ASSERT_TRUE(acceptReplay(p, r, {}));
  auto accepted = [&](Phase planned, const std::string& seen) {
    for (PlanSegment& seg : p.segments) seg.phase = planned;
    r.phases = seen;
    return acceptReplay(p, r, {});
  };
  // Ending at rest: the replay may add one run with more sticking contacts, nothing else.
  p.samples.back().v.setZero();
  EXPECT_TRUE(accepted(Phase::kU, "UP"));
  EXPECT_TRUE(accepted(Phase::kU, "UC"));
  EXPECT_TRUE(accepted(Phase::kP, "PC"));
  EXPECT_FALSE(accepted(Phase::kP, "PU"));  // less sticking: a slide the plan does not make
  EXPECT_FALSE(accepted(Phase::kC, "CP"));
  EXPECT_FALSE(accepted(Phase::kU, "UPU"));  // not a last run
  EXPECT_FALSE(accepted(Phase::kU, "UPC"));  // more than one
  EXPECT_FALSE(accepted(Phase::kU, "P"));    // the planned run missing
  // The part still moving at the plan's end (by more than rest_speed in any of x, y, phi):
  // a trailing sticking run is a mode the plan does not have.
  for (int k = 0; k < layout::kObjectDim; ++k) {
    p.samples.back().v.setZero();
    p.samples.back().v[k] = 2e-3;
    EXPECT_FALSE(accepted(Phase::kU, "UP")) << "coordinate " << k;
  }
  ReplaySettings loose;
  loose.rest_speed = 3e-3;
  r.phases = "UP";
  EXPECT_TRUE(acceptReplay(p, r, loose));
}

TEST_F(PlanReplayTest, AngleErrorIsMeasuredAgainstTheTurnThePlanMakes) {
  // The goal angle is read within pi of the plan's final angle, so the same plan aimed at
  // a goal one turn further ("absolute" 345 deg instead of -15 deg) still verifies, and a
  // plan whose samples end a whole turn away from where the part really ends does not.
  Plan turned = *plan_;
  turned.goal.phi += 2.0 * M_PI;
  const ReplayResult same = replayPlan(planner_->simulator(), turned, nullptr, {});
  const ReplayResult base = replayPlan(planner_->simulator(), *plan_, nullptr, {});
  EXPECT_NEAR(same.angle_error, base.angle_error, 1e-9);
  Plan lying = *plan_;  // its samples (the reference) claim a full extra turn
  for (PlanSample& s : lying.samples) s.q[layout::kPhi] += 2.0 * M_PI;
  lying.goal.phi += 2.0 * M_PI;
  const ReplayResult r = replayPlan(planner_->simulator(), lying, nullptr, {});
  EXPECT_NEAR(r.angle_error, 2.0 * M_PI, 0.05);
  EXPECT_FALSE(acceptReplay(lying, r, {}));
}

TEST_F(PlanReplayTest, OptimisationAndReplayKeysRoundTrip) {
  Plan plan = *plan_;
  plan.segments[0].tau_end = plan.segments[0].tau * 0.5;
  plan.optimization = {true, "Solve_Succeeded", 42, 0.25, 123.5, 67.25, "rejected: because"};
  plan.replay = verifyPlan(planner_->simulator(), plan, {});
  plan.planner_replay = verifyPlan(planner_->simulator(), *plan_, {});
  plan.planner_replay.closed_loop.phases = "CPU";  // distinct from `replay`'s
  plan.replay.closed_loop.departure_time = 0.75;
  plan.replay.closed_loop.departure_phase = "U";
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_opt_plan.json";
  writePlanJson(plan, path);
  const Plan back = readPlanJson(path);
  EXPECT_TRUE(back.segments[0].tau_end == plan.segments[0].tau_end);
  EXPECT_EQ(back.segments[1].tau_end.size(), 0);
  const OptimizationSummary& o = back.optimization;
  EXPECT_TRUE(o.ran);
  EXPECT_EQ(o.status, "Solve_Succeeded");
  EXPECT_EQ(o.iterations, 42);
  EXPECT_EQ(o.solve_time, 0.25);
  EXPECT_EQ(o.cost_before, 123.5);
  EXPECT_EQ(o.cost_after, 67.25);
  EXPECT_EQ(o.message, "rejected: because");
  const ReplaySummary& r = back.replay;
  EXPECT_TRUE(r.ran);
  EXPECT_EQ(r.accepted, plan.replay.accepted);
  EXPECT_EQ(r.closed_loop.position_error, plan.replay.closed_loop.position_error);
  EXPECT_EQ(r.closed_loop.angle_error, plan.replay.closed_loop.angle_error);
  EXPECT_EQ(r.closed_loop.min_f_n, plan.replay.closed_loop.min_f_n);
  EXPECT_EQ(r.closed_loop.phases, plan.replay.closed_loop.phases);
  EXPECT_EQ(r.closed_loop.max_tracking_error, plan.replay.closed_loop.max_tracking_error);
  EXPECT_EQ(r.closed_loop.departure_time, 0.75);
  EXPECT_EQ(r.closed_loop.departure_phase, "U");
  EXPECT_EQ(r.open_loop.departure_time, plan.replay.open_loop.departure_time);
  EXPECT_EQ(r.open_loop.departure_phase, plan.replay.open_loop.departure_phase);
  EXPECT_EQ(r.open_loop.position_error, plan.replay.open_loop.position_error);
  EXPECT_EQ(r.open_loop.phases, plan.replay.open_loop.phases);
  const ReplaySummary& k = back.planner_replay;
  EXPECT_TRUE(k.ran);
  EXPECT_EQ(k.accepted, plan.planner_replay.accepted);
  EXPECT_EQ(k.closed_loop.phases, "CPU");
  EXPECT_EQ(k.closed_loop.position_error, plan.planner_replay.closed_loop.position_error);
  EXPECT_EQ(k.closed_loop.max_tracking_error, plan.planner_replay.closed_loop.max_tracking_error);
  EXPECT_EQ(k.open_loop.angle_error, plan.planner_replay.open_loop.angle_error);
  // Without the optimiser neither key is written, and none comes back.
  writePlanJson(*plan_, path);
  EXPECT_FALSE(readPlanJson(path).optimization.ran);
  EXPECT_FALSE(readPlanJson(path).replay.ran);
  EXPECT_FALSE(readPlanJson(path).planner_replay.ran);
  std::remove(path.c_str());
}

TEST_F(PlanReplayTest, MalformedOptimisationKeysAreNamed) {
  Plan plan = *plan_;
  plan.optimization = {true, "Solve_Succeeded", 42, 0.25, 123.5, 67.25, ""};
  plan.replay = verifyPlan(planner_->simulator(), plan, {});
  plan.planner_replay = plan.replay;
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_bad_opt.json";
  writePlanJson(plan, path);
  std::ifstream in(path);
  nlohmann::json j = nlohmann::json::parse(in);
  in.close();
  auto expectRefused = [&](const nlohmann::json& bad, const std::string& key) {
    { std::ofstream(path) << bad.dump(); }
    try {
      readPlanJson(path);
      ADD_FAILURE() << "accepted without " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  nlohmann::json bad = j;
  bad["optimization"]["iterations"] = "many";
  expectRefused(bad, "optimization.iterations");
  bad = j;
  bad.erase("accepted");
  expectRefused(bad, "accepted");
  bad = j;
  bad["replay"]["closed_loop"].erase("max_tracking_error");
  expectRefused(bad, "replay.closed_loop.max_tracking_error");
  bad = j;
  bad["replay"]["open_loop"]["phases"] = 3;
  expectRefused(bad, "replay.open_loop.phases");
  bad = j;
  bad["planner_replay"].erase("accepted");
  expectRefused(bad, "planner_replay.accepted");
  bad = j;
  bad["planner_replay"]["open_loop"]["min_f_n"] = "none";
  expectRefused(bad, "planner_replay.open_loop.min_f_n");
  bad = j;
  bad["replay"]["closed_loop"]["departure_time"] = 0.5;  // without its phase
  expectRefused(bad, "replay.closed_loop.departure_phase");
  bad["replay"]["closed_loop"]["departure_phase"] = "X";
  expectRefused(bad, "departure_phase C, P or U");
  bad["replay"]["closed_loop"]["departure_phase"] = "P";
  bad["replay"]["closed_loop"]["departure_time"] = -2.0;
  expectRefused(bad, "departure_time must be >= 0");
  bad = j;
  bad["segments"][0]["tau_end"] = {1.0};
  expectRefused(bad, "tau_end");
  std::remove(path.c_str());
}

TEST(PhaseRuns, ShortRunsDroppedAndNeighboursMerged) {
  using R = std::vector<std::pair<Phase, double>>;
  EXPECT_EQ(filterPhaseRuns(R{{Phase::kC, 0.1}, {Phase::kU, 0.005}, {Phase::kC, 0.2}}, 0.02), "C");
  EXPECT_EQ(filterPhaseRuns(R{{Phase::kC, 0.1}, {Phase::kU, 0.05}, {Phase::kC, 0.2}}, 0.02), "CUC");
  EXPECT_EQ(filterPhaseRuns(R{{Phase::kP, 0.01}, {Phase::kP, 0.015}, {Phase::kU, 0.3}}, 0.02),
            "PU");
  EXPECT_EQ(filterPhaseRuns(R{{Phase::kP, 0.01}, {Phase::kU, 0.015}}, 0.02), "U");
  EXPECT_EQ(filterPhaseRuns(R{}, 0.02), "");
}

}  // namespace
}  // namespace rbsf::planner
