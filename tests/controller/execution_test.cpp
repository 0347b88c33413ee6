// The execution status, guard and hold of track() (plan_executor.h), on the project's
// simulator as the cell with the cell's noisy sensors: a part pushed off its tube is reported
// within 20 ms of leaving it and held on the fingers; a hold anywhere on a plan rests the part
// where the plan was; non-finite readings never reach the law; certified trials never say
// "leaving".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/control/plan_executor.h"
#include "rbsf/dynamics/control/sensor_model.h"
#include "rbsf/dynamics/core/model_data.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/plan/trial.h"
#include "support_plan_file.h"
#include "test_support.h"

namespace rbsf::controller {
namespace {

/// The -30 degree support plan of the default cell as the pipeline writes it (refined where
/// at least as good), in a file, once per test binary.
const std::string& turnFile() {
  static const std::string path = plannedFile(-30.0, true, 8, 0.6, "turn30");
  return path;
}

/// The nominal cell driven by a controller through track(): its sensors the cell's (noise
/// on, a fixed seed), the part's pose handed to addPartPose() when it arrives.
struct CellRun {
  CellRun(ReorientationController& c, const plan::Plan& plan)
      : controller(c),
        model(c.model()),
        sim(model, plan.simulator),
        ws(model.numFingers()),
        sensors(model.cell().sensing, plan.simulator.time_step, 11),
        state(plan::nominalDraw(model.cell(), plan).q0, VecQ::Zero(plan.q0.size())),
        h(plan.simulator.time_step),
        joints(model.controlDim()) {}

  /// One tick at step n: measure, track, step the plant. False when the plant diverged.
  bool tick(long n) {
    sensors.joints(state.q, joints);
    sensors.partPose(n, state.q, [&](double s, const Pose& p) { controller.addPartPose(s, p); });
    if (!controller.track(n * h, joints, tau, status)) return false;
    sim.step(state, tau, ws);
    return state.q.allFinite();
  }
  /// Fingers within 1 mm of the part.
  int touching() const {
    ModelData data(model.numFingers());
    model.updateContacts(state.q, data);
    int n = 0;
    for (int i = 0; i < model.numFingers(); ++i) n += data.contacts[i].gap < 1e-3;
    return n;
  }
  double speed() const { return std::hypot(state.v[layout::kX], state.v[layout::kY]); }

  ReorientationController& controller;
  const RbsfModel& model;
  Simulator sim;
  SimulatorWorkspace ws;
  SensorModel sensors;
  SimState state;
  double h;
  VecU joints, tau;
  ExecutionStatus status;
};

/// Pushed sideways at 5 cm/s two seconds into the plan, while the part pivots: the first
/// time the status says "leaving" (-1: never) and the first time the part is off its tube,
/// its pose beyond the leaving band from the plan's reference (-1: never within `after`).
struct Push {
  double reported = -1.0, off = -1.0;
};
Push push(ReorientationController& c, const plan::Plan& plan, CellRun& run, double after) {
  const ExecutionLimits limits;
  const FeedbackSchedule schedule(c.model(), plan::makeReference(plan), c.model().cell().sensing,
                                  plan.simulator);
  const long kick = std::lround(2.0 / run.h);
  Push p;
  for (long n = 0; n < kick + std::lround(after / run.h); ++n) {
    if (n == kick) run.state.v[layout::kX] -= 0.05;
    if (!run.tick(n)) break;
    if (n < kick) {
      EXPECT_EQ(run.status.flags & kFlagOffTube, 0u) << "t = " << n * run.h;
    }
    if (p.reported < 0.0 && run.status.verdict == ExecutionVerdict::kLeaving)
      p.reported = run.status.plan_time;
    ReferenceSample ref;
    schedule.reference((n + 1) * run.h, ref);
    const double dp = std::hypot(run.state.q[layout::kX] - ref.q[layout::kX],
                                 run.state.q[layout::kY] - ref.q[layout::kY]);
    const double da = std::abs(run.state.q[layout::kPhi] - ref.q[layout::kPhi]);
    if (p.off < 0.0 && (dp > limits.leaving_position || da > limits.leaving_angle))
      p.off = (n + 1) * run.h;
  }
  return p;
}

TEST(ExecutionStatus, APartPushedOffCourseIsReportedWithin20msAndHeldOnTheFingersFor5s) {
  const plan::Plan plan = plan::readPlanJson(turnFile()).plan;
  std::string why;
  // Where the pushed part leaves its tube: the same run with the hold off (the status still
  // watches), until then the run below, tick for tick.
  ExecutionLimits watch_only;
  watch_only.hold_on_leaving = false;
  ReorientationController unheld(kDefaultCell, FeedbackSettings{}, watch_only);
  ASSERT_TRUE(unheld.loadFile(turnFile(), &why)) << why;
  CellRun free_run(unheld, plan);
  const Push left = push(unheld, plan, free_run, 2.0);
  ASSERT_GT(left.off, 2.0) << "the push did not take the part off its tube";
  ASSERT_GT(left.reported, 2.0) << "never reported leaving";
  EXPECT_LE(left.reported, left.off + 0.02) << "off the tube at " << left.off;

  ReorientationController c(kDefaultCell);
  ASSERT_TRUE(c.loadFile(turnFile(), &why)) << why;
  CellRun run(c, plan);
  const Push held = push(c, plan, run, left.reported - 2.0 + 0.5 * run.h);
  EXPECT_EQ(held.reported, left.reported);
  // Held from the next tick, for 5 s: on the fingers all along, at rest at the end, near
  // where it was reported.
  const VecQ at_report = run.state.q;
  for (long n = std::lround(left.reported / run.h) + 1, end = n + std::lround(5.0 / run.h); n < end;
       ++n) {
    ASSERT_TRUE(run.tick(n));
    ASSERT_GE(run.touching(), 2) << "t = " << n * run.h;
    ASSERT_EQ(run.status.verdict, ExecutionVerdict::kHolding);
    ASSERT_EQ(run.status.hold_reason, HoldReason::kLeaving);
  }
  EXPECT_LT(run.speed(), 1e-3);
  EXPECT_LT(std::abs(run.state.v[layout::kPhi]), 0.2 * M_PI / 180.0);
  EXPECT_LT(std::hypot(run.state.q[0] - at_report[0], run.state.q[1] - at_report[1]), 0.03);
  Pose part;
  double theta = 0.0;
  ASSERT_TRUE(c.heldState(part, theta));
  EXPECT_LT(std::abs(theta - run.state.q[layout::kTheta]), 1e-3);
}

TEST(ExecutionStatus, AHoldAnywhereOnThePlanRestsThePartWhereThePlanWas) {
  const plan::Plan plan = plan::readPlanJson(turnFile()).plan;
  for (const double fraction : {0.25, 0.5, 0.75}) {
    ReorientationController c(kDefaultCell);
    std::string why;
    ASSERT_TRUE(c.loadFile(turnFile(), &why)) << why;
    CellRun run(c, plan);
    const long at = std::lround(fraction * plan.duration() / run.h);
    long n = 0;
    for (; n < at; ++n) ASSERT_TRUE(run.tick(n));
    const VecQ before = run.state.q;
    c.hold();
    for (const long end = n + std::lround(5.0 / run.h); n < end; ++n) {
      ASSERT_TRUE(run.tick(n));
      ASSERT_GE(run.touching(), 2) << fraction << " of the plan, t = " << n * run.h;
    }
    EXPECT_EQ(run.status.verdict, ExecutionVerdict::kHolding);
    EXPECT_EQ(run.status.hold_reason, HoldReason::kCommanded);
    EXPECT_LT(run.speed(), 1e-3) << fraction;
    EXPECT_LT(std::abs(run.state.v[layout::kPhi]), 0.2 * M_PI / 180.0) << fraction;
    EXPECT_LT(std::hypot(run.state.q[0] - before[0], run.state.q[1] - before[1]), 0.02) << fraction;
    EXPECT_LT(std::abs(run.state.q[layout::kPhi] - before[layout::kPhi]), 3.0 * M_PI / 180.0)
        << fraction;
    // start() releases the hold: a fresh run from the plan's start.
    c.start();
    ASSERT_TRUE(c.track(0.0, run.joints, run.tau, run.status));
    EXPECT_NE(run.status.verdict, ExecutionVerdict::kHolding);
  }
}

TEST(ExecutionStatus, ARunStartedAgainRepeatsTheFirstRunBitForBit) {
  // start() resets the law: the same readings give the same inputs, to the last bit (the
  // closest-point searches included, which would otherwise start from the last run's).
  const plan::Plan plan = plan::readPlanJson(turnFile()).plan;
  ReorientationController c(kDefaultCell);
  std::string why;
  ASSERT_TRUE(c.loadFile(turnFile(), &why)) << why;
  std::vector<VecU> first;
  {
    CellRun run(c, plan);
    for (long n = 0; n < 1500; ++n) {
      ASSERT_TRUE(run.tick(n));
      first.push_back(run.tau);
    }
  }
  c.start();
  CellRun again(c, plan);
  for (long n = 0; n < 1500; ++n) {
    ASSERT_TRUE(again.tick(n));
    ASSERT_TRUE((again.tau.array() == first[static_cast<std::size_t>(n)].array()).all())
        << "tick " << n;
  }
}

TEST(ExecutionStatus, AResumedRunPlansFromWhereItIsHeldAndReachesTheGoal) {
  const plan::Plan plan = plan::readPlanJson(turnFile()).plan;
  ReorientationController c(kDefaultCell);
  std::string why;
  ASSERT_TRUE(c.loadFile(turnFile(), &why)) << why;
  CellRun run(c, plan);
  long n = 0;
  for (const long at = std::lround(0.5 * plan.duration() / run.h); n < at; ++n)
    ASSERT_TRUE(run.tick(n));
  c.hold();
  for (const long end = n + std::lround(1.0 / run.h); n < end; ++n) ASSERT_TRUE(run.tick(n));
  Pose held;
  double theta = 0.0;
  ASSERT_TRUE(c.heldState(held, theta));
  ReorientationRequest r;
  r.problem.goal = plan.goal;
  r.method = planner::PipelineMethod::kAuto;
  r.planner = rbsf::test::withoutClock(r.planner);
  r.planner.max_propagations = 200000;
  r.support.max_expansions = 100000;
  r.certificate.trials = 4;
  r.certificate.required_rate = 0.4;
  r.accept_uncertified = true;
  ASSERT_TRUE(c.resume(r));
  // The loop keeps holding while the worker plans (the held plan stays published).
  while (c.status() == ControllerStatus::kPlanning) ASSERT_TRUE(run.tick(n++));
  c.wait();
  ASSERT_EQ(c.status(), ControllerStatus::kReady) << c.result().message;
  EXPECT_EQ(c.planId(), 2u);
  const plan::Plan& again = c.result().record.plan;
  EXPECT_NEAR(again.start.x, held.x, 1e-9);
  EXPECT_NEAR(again.start_theta, theta, 1e-9);
  // The new plan from its t = 0, the plant where the hold left it.
  const long steps = std::lround((again.duration() + 1.0) / run.h);
  for (long k = 0; k < steps; ++k) {
    run.sensors.joints(run.state.q, run.joints);
    ASSERT_TRUE(c.track(k * run.h, run.joints, run.tau, run.status));
    run.sim.step(run.state, run.tau, run.ws);
    ASSERT_TRUE(run.state.q.allFinite());
  }
  EXPECT_NE(run.status.verdict, ExecutionVerdict::kHolding) << toString(run.status.hold_reason);
  EXPECT_LT(std::hypot(run.state.q[0] - plan.goal.x, run.state.q[1] - plan.goal.y), 0.01);
  EXPECT_LT(std::abs(run.state.q[2] - plan.goal.phi), 2.0 * M_PI / 180.0);
}

TEST(ExecutionStatus, AHoldSlowsThePlansTimeToAStopAndItsReferenceToRest) {
  // s' = 1 - (t - t_h) / hold_stop: the plan's time stops at t_h + hold_stop / 2, and the
  // reference's velocity is the plan's times s', zero from then on.
  const plan::Plan plan = plan::readPlanJson(turnFile()).plan;
  const RbsfModel model(loadCell(kDefaultCell));
  const FeedbackSchedule schedule(model, plan::makeReference(plan),
                                  plan::lawSensing(model.cell().sensing, plan), plan.simulator);
  PlanExecutor executor(schedule);
  const double h = plan.simulator.time_step, T = schedule.settings().timing.hold_stop;
  const double th = std::round(0.5 * plan.duration() / h) * h;  // a tick
  VecU joints(model.controlDim()), tau;
  ReferenceSample at;
  for (long n = 0; n * h <= th + 1.0; ++n) {
    const double t = n * h;
    schedule.reference(executor.law().planTime(t), at);
    for (int j = 0; j < joints.size(); ++j) joints[j] = at.q[layout::inputToConfig(j)];
    executor.step(t, joints, tau);
    if (std::abs(t - th) < 0.5 * h) executor.hold();
    const ControlLaw& law = executor.law();
    if (t <= th + 0.5 * h) {
      EXPECT_EQ(law.planTime(t), t);
      continue;
    }
    double rate = 0.0;
    const double s = law.planTime(t, &rate);
    const double d = std::min(t - th, T);
    EXPECT_NEAR(s, th + d - 0.5 * d * d / T, 1e-12) << "t = " << t;
    EXPECT_NEAR(rate, 1.0 - d / T, 1e-12) << "t = " << t;
    ReferenceSample planned;
    schedule.reference(s, planned);
    EXPECT_LT((law.reference().v - rate * planned.v).cwiseAbs().maxCoeff(), 1e-12) << "t = " << t;
    if (t - th > T) {
      EXPECT_TRUE(law.reference().v.isZero()) << "t = " << t;
    }
  }
  EXPECT_EQ(executor.status().verdict, ExecutionVerdict::kHolding);
}

TEST(ExecutionStatus, NonFiniteReadingsNeverReachTheLaw) {
  const plan::Plan plan = plan::readPlanJson(planFile()).plan;
  const RbsfModel model(loadCell(kDefaultCell));
  const FeedbackSchedule schedule(model, plan::makeReference(plan),
                                  plan::lawSensing(model.cell().sensing, plan), plan.simulator);
  PlanExecutor guarded(schedule), plain(schedule);
  const double h = plan.simulator.time_step, nan = std::numeric_limits<double>::quiet_NaN();
  const long bad = std::lround(1.0 / h);
  VecU joints(model.controlDim()), last(model.controlDim()), tau, want;
  for (long n = 0; n <= bad + 40; ++n) {
    ReferenceSample ref;
    schedule.reference(n * h, ref);
    for (int j = 0; j < joints.size(); ++j)
      joints[j] = ref.q[layout::inputToConfig(j)] + 2e-5 * std::sin(0.01 * n + j);
    if (n < bad) last = joints;
    VecU reading = joints;
    if (n == bad) reading[1] = nan;                                          // one spike
    if (n >= bad + 5) reading[2] = std::numeric_limits<double>::infinity();  // then a dead sensor
    if (n == bad + 2) guarded.addPartPose(n * h, Pose{nan, 0.0, 0.0});
    guarded.step(n * h, reading, tau);
    const ExecutionStatus& s = guarded.status();
    ASSERT_TRUE(tau.allFinite()) << "t = " << n * h;
    if (n == bad) {
      // The last good reading serves: the input of a law that was given it.
      plain.step(n * h, last, want);
      EXPECT_EQ(tau, want);
      EXPECT_TRUE(s.flags & kFlagBadJoints);
      EXPECT_EQ(s.verdict, ExecutionVerdict::kDegraded);
    } else if (n < bad + 5) {
      plain.step(n * h, reading, want);
      EXPECT_EQ(tau, want) << "t = " << n * h;
    }
    if (n == bad + 2) {
      EXPECT_TRUE(s.flags & kFlagBadPose);
    }
    // A reading dead for bad_joint_time holds the part, on the last good reading.
    const long dead = n - (bad + 5);
    if (dead * h < guarded.limits().bad_joint_time) {
      EXPECT_NE(s.verdict, ExecutionVerdict::kHolding) << "t = " << n * h;
    }
    if (dead * h > guarded.limits().bad_joint_time + 1.5 * h) {
      EXPECT_EQ(s.verdict, ExecutionVerdict::kHolding) << "t = " << n * h;
      EXPECT_EQ(s.hold_reason, HoldReason::kBadJoints);
    }
  }
  EXPECT_EQ(guarded.status().bad_readings, 1u + 1u + 36u);
  // A non-finite time holds the last input.
  const VecU before = tau;
  guarded.step(nan, joints, tau);
  EXPECT_EQ(tau, before);
  EXPECT_TRUE(guarded.status().flags & kFlagBadTime);
}

TEST(ExecutionStatus, CertifiedTrialsNeverSayLeaving) {
  // The false alarm a hold would pay for: trials of the certified plan under the cell's
  // uncertainty and noise succeed, and their status never says "leaving".
  const RbsfModel model(loadCell(kDefaultCell));
  const plan::Plan plan = plan::readPlanJson(turnFile()).plan;
  plan::CertificateSettings settings;
  for (int i = 0; i < 6; ++i) {
    std::vector<TrajectorySample> trace;
    const plan::TrialOutcome o = plan::traceTrial(model, plan, settings, i, trace);
    EXPECT_TRUE(o.success) << "trial " << i << ": " << o.failure;
    EXPECT_LT(o.leaving_time, 0.0) << "trial " << i;
    EXPECT_LT(o.status_position, ExecutionLimits{}.leaving_position) << "trial " << i;
    EXPECT_GT(o.status_position, 0.0) << "trial " << i;
  }
}

}  // namespace
}  // namespace rbsf::controller
