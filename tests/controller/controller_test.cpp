// The controller facade (rbsf/controller/reorientation_controller.h): a plan completes and
// sampling returns its values at its knots; sampling while a new request plans returns
// the previous plan (or "no plan" before any); cancel ends a request with a cancelled
// status; progress is reported; snapshots are never torn. Also run under ThreadSanitizer
// (scripts/rbsf.sh tsan).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "../../executor/src/snapshot_slots.h"
#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/control/plan_executor.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/plan_reference.h"

namespace rbsf::controller {
namespace {

const std::string kDefaultCell = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";

/// The planner tests' small problem: a 15 degree turn, solved exactly with seed 4.
ReorientationRequest smallRequest(std::uint32_t seed = 4, double degrees = -15.0) {
  ReorientationRequest r;
  r.problem.start = {0.1, 0.40, 0.0};
  r.problem.goal = {0.1, 0.40, degrees * M_PI / 180.0};
  r.planner.seed = seed;
  r.planner.time_limit = 120.0;  // generous: the search ends at the goal (sanitizers are slow)
  r.planner.max_propagations = 200000;  // and well within this budget
  r.certificate.trials = 4;             // the facade's threading, not the plan, is under test
  r.certificate.required_rate = 0.4;    // 4 of 4 trials bound the rate at 0.47: certified
  r.accept_uncertified = true;
  return r;
}

/// track() runs the executor of published plan `id` (the control law behind its guard, with
/// its status and hold): the same inputs and verdicts as an executor built here on the plan's
/// own schedule and law (lawSensing: a joint-fed plan gets the joint law whatever the cell
/// senses), fed the same joints and, every 10th step, the same part poses, over plan times
/// [0, until].
void expectTrackRunsThePlansLaw(ReorientationController& c, const plan::Plan& plan,
                                std::uint64_t id, double until) {
  const FeedbackSchedule schedule(c.model(), plan::makeReference(plan),
                                  plan::lawSensing(c.model().cell().sensing, plan), plan.simulator);
  PlanExecutor executor(schedule);
  VecU tau, want;
  const double h = plan.simulator.time_step;
  for (long k = 0; k * h <= until; ++k) {
    const double t = k * h;
    ReferenceSample at;
    schedule.reference(t, at);
    VecU joints(c.model().controlDim());
    for (int j = 0; j < joints.size(); ++j)
      joints[j] = at.q[layout::inputToConfig(j)] + 1e-4 * std::sin(0.01 * k + j);
    if (k % 10 == 0) {
      const Pose pose{at.q[layout::kX] + 1e-4, at.q[layout::kY], at.q[layout::kPhi]};
      c.addPartPose(t, pose);
      executor.addPartPose(t, pose);
    }
    std::uint64_t tracked = 0;
    ExecutionStatus status;
    ASSERT_TRUE(c.track(t, joints, tau, status, &tracked));
    EXPECT_EQ(tracked, id);
    executor.step(t, joints, want);
    ASSERT_EQ(tau, want) << "t = " << t;
    ASSERT_EQ(status.verdict, executor.status().verdict) << "t = " << t;
    ASSERT_EQ(status.position_deviation, executor.status().position_deviation) << "t = " << t;
  }
}

/// A request the search cannot finish: tolerances of a micrometre and a microradian.
ReorientationRequest endlessRequest() {
  ReorientationRequest r = smallRequest(1, -90.0);
  r.problem.tolerance = {1e-6, 1e-6};
  r.planner.time_limit = 300.0;
  return r;
}

TEST(ReorientationController, NoPlanBeforeTheFirstRequest) {
  ReorientationController c(kDefaultCell);
  EXPECT_EQ(c.status(), ControllerStatus::kIdle);
  EXPECT_EQ(c.outcome(), PlanOutcome::kNone);
  EXPECT_EQ(c.planId(), 0u);
  ReferenceSample out;
  out.t = -42.0;  // untouched by a "no plan" sample
  EXPECT_FALSE(c.sample(0.5, out));
  EXPECT_EQ(out.t, -42.0);
  const VecU joints = VecU::Zero(c.model().controlDim());
  VecU tau = VecU::Constant(c.model().controlDim(), 7.0);
  EXPECT_FALSE(c.track(0.5, joints, tau));
  EXPECT_TRUE((tau.array() == 7.0).all());
}

TEST(ReorientationController, PlanCompletesAndSamplingReturnsItsKnots) {
  ReorientationController c(kDefaultCell);
  ASSERT_TRUE(c.plan(smallRequest()));
  c.wait();
  ASSERT_EQ(c.status(), ControllerStatus::kReady) << c.result().message;
  const RequestResult result = c.result();
  const plan::Plan& plan = result.record.plan;
  const plan::Certificate& certificate = result.record.certificate;
  ASSERT_EQ(plan.status, plan::PlanStatus::kExact);
  // Published with its certificate; the outcome says whether it earned it.
  ASSERT_TRUE(certificate.ran);
  EXPECT_EQ(certificate.trials, 4);
  EXPECT_EQ(c.outcome(), certificate.certified ? PlanOutcome::kExact : PlanOutcome::kNotCertified);
  EXPECT_NE(result.message.find("certified"), std::string::npos) << result.message;
  EXPECT_EQ(result.plan_id, 1u);
  EXPECT_EQ(c.planId(), 1u);

  double duration = 0.0;
  VecQ q0;
  ASSERT_TRUE(c.publishedPlan(duration, q0));
  EXPECT_DOUBLE_EQ(duration, plan.duration());
  EXPECT_EQ(q0, plan.q0);

  // At every knot: the plan's q and v (the reference interpolates through them).
  ReferenceSample ref;
  std::uint64_t id = 0;
  for (const plan::PlanSample& s : plan.samples) {
    ASSERT_TRUE(c.sample(s.t, ref, &id));
    EXPECT_EQ(id, 1u);
    EXPECT_LE((ref.q - s.q).cwiseAbs().maxCoeff(), 1e-9) << "t = " << s.t;
    EXPECT_LE((ref.v - s.v).cwiseAbs().maxCoeff(), 1e-9) << "t = " << s.t;
  }
  // Inside every segment: its held tau and its simulated phase.
  double t0 = 0.0;
  for (const plan::PlanSegment& seg : plan.segments) {
    ASSERT_TRUE(c.sample(t0 + 0.5 * seg.duration, ref));
    EXPECT_EQ(ref.tau, seg.tau);
    EXPECT_EQ(ref.phase, seg.phase);
    t0 += seg.duration;
  }
  expectTrackRunsThePlansLaw(c, plan, 1u, plan.duration());
}

TEST(ReorientationController, SamplingDuringPlanningReturnsThePreviousPlanAndCancelStops) {
  ReorientationController c(kDefaultCell);
  ASSERT_TRUE(c.plan(smallRequest()));
  c.wait();
  ASSERT_EQ(c.status(), ControllerStatus::kReady);
  const plan::Plan first = c.result().record.plan;
  const ReferenceTrajectory expected = plan::makeReference(first);

  // A request that cannot finish; its progress callback cancels it after one report.
  std::atomic<int> reports{0};
  std::atomic<double> elapsed_at_report{0.0};
  ReorientationRequest endless = endlessRequest();
  endless.progress = [&](const planner::Progress& p) {
    elapsed_at_report.store(p.elapsed);
    if (reports.fetch_add(1) == 0) c.cancel();
  };
  ASSERT_TRUE(c.plan(endless));
  EXPECT_FALSE(c.plan(smallRequest())) << "a second request while one is planning";

  // Sample from this thread while the worker plans: always the first plan, exactly.
  ReferenceSample got, want;
  std::uint64_t id = 0;
  long samples = 0;
  const double T = first.duration();
  while (c.status() == ControllerStatus::kPlanning) {
    const double t = std::fmod(1e-3 * samples, T + 0.2) - 0.1;
    ASSERT_TRUE(c.sample(t, got, &id));
    expected.sample(t, want);
    ASSERT_EQ(id, 1u);
    ASSERT_EQ(got.q, want.q);
    ASSERT_EQ(got.tau, want.tau);
    ++samples;
  }
  c.wait();
  EXPECT_GT(samples, 0);
  EXPECT_EQ(c.status(), ControllerStatus::kFailed);
  EXPECT_EQ(c.outcome(), PlanOutcome::kCancelled);
  EXPECT_GE(reports.load(), 1);
  EXPECT_GT(elapsed_at_report.load(), 0.5);  // reports come about once per second
  // Stopped by the cancel, long before its 300 s time limit.
  const RequestResult cancelled = c.result();
  EXPECT_LT(cancelled.record.plan.planning_time, 0.5 * endless.planner.time_limit);
  EXPECT_EQ(cancelled.plan_id, 0u);
  EXPECT_EQ(c.planId(), 1u);  // the first plan stays published
  ASSERT_TRUE(c.sample(0.3, got, &id));
  EXPECT_EQ(id, 1u);

  // Re-plan: the new plan replaces the first.
  ASSERT_TRUE(c.plan(smallRequest(3, -20.0)));
  c.wait();
  ASSERT_EQ(c.status(), ControllerStatus::kReady) << c.result().message;
  EXPECT_EQ(c.planId(), 2u);
  const plan::Plan second = c.result().record.plan;
  const plan::PlanSample& last = second.samples.back();
  ASSERT_TRUE(c.sample(last.t, got, &id));
  EXPECT_EQ(id, 2u);
  EXPECT_LE((got.q - last.q).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ReorientationController, CancelFromAnotherThreadAndDestructionWhilePlanning) {
  ReorientationController c(kDefaultCell);
  ASSERT_TRUE(c.plan(endlessRequest()));
  std::thread canceller([&] { c.cancel(); });
  canceller.join();
  c.wait();
  EXPECT_EQ(c.status(), ControllerStatus::kFailed);
  EXPECT_EQ(c.outcome(), PlanOutcome::kCancelled);
  EXPECT_EQ(c.planId(), 0u);
  ReferenceSample out;
  EXPECT_FALSE(c.sample(0.0, out));
  // The destructor cancels and joins a running request.
  auto d = std::make_unique<ReorientationController>(kDefaultCell);
  ASSERT_TRUE(d->plan(endlessRequest()));
  d.reset();
}

TEST(ReorientationController, AutoPlansWithSupportsFirstAndTracksWithTheJointLaw) {
  // kAuto: the support planner's slow plan certifies, is published, and track() runs the
  // joint law that plan carries (lawSensing), whatever the cell senses.
  ReorientationController c(kDefaultCell);
  ReorientationRequest r = smallRequest();
  r.method = planner::PipelineMethod::kAuto;
  r.accept_uncertified = false;
  ASSERT_TRUE(c.plan(r));
  c.wait();
  ASSERT_EQ(c.status(), ControllerStatus::kReady) << c.result().message;
  EXPECT_EQ(c.outcome(), PlanOutcome::kExact);
  const plan::PlanRecord record = c.result().record;
  const plan::Plan& plan = record.plan;
  EXPECT_EQ(plan.planner, "support");
  EXPECT_TRUE(plan.joint_feedback);
  EXPECT_TRUE(record.certificate.certified);
  EXPECT_EQ(record.certificate.law, plan::TrialLaw::kJointFeedback);
  expectTrackRunsThePlansLaw(c, plan, 1u, 1.0);
}

TEST(ReorientationController, RefusedProblemFailsWithItsMessage) {
  ReorientationController c(kDefaultCell);
  ReorientationRequest r = smallRequest();
  r.problem.goal = {3.0, 0.40, 0.0};  // no finger reaches a part 3 m away
  ASSERT_TRUE(c.plan(r));
  c.wait();
  EXPECT_EQ(c.status(), ControllerStatus::kFailed);
  EXPECT_EQ(c.outcome(), PlanOutcome::kInputError);
  EXPECT_NE(c.result().message.find("goal"), std::string::npos) << c.result().message;
  r.planner.max_control_steps = 0;
  r.problem.goal = smallRequest().problem.goal;
  ASSERT_TRUE(c.plan(r));
  c.wait();
  EXPECT_EQ(c.outcome(), PlanOutcome::kInputError);
  EXPECT_NE(c.result().message.find("control steps"), std::string::npos) << c.result().message;
}

// Snapshots published while readers read are never seen half-written, and a reader never
// sees an older snapshot after a newer one.
TEST(SnapshotSlots, ReadersSeeWholeSnapshotsInOrder) {
  struct Snapshot {
    long id;
    std::vector<long> values;  // all equal to id
  };
  executor::detail::SnapshotSlots<Snapshot> slots;
  constexpr long kPublications = 2000;
  std::atomic<bool> done{false};
  std::atomic<long> torn{0}, backwards{0}, reads{0};
  auto reader = [&] {
    long last = 0;
    while (!done.load()) {
      const executor::detail::SnapshotSlots<Snapshot>::Reader r(slots);
      const Snapshot* s = r.get();
      if (s == nullptr) continue;
      for (long v : s->values) torn += v != s->id;
      backwards += s->id < last;
      last = s->id;
      ++reads;
    }
  };
  std::thread r1(reader), r2(reader);
  // Let both readers hold the first snapshot before the publications race them.
  slots.publish(std::make_unique<const Snapshot>(Snapshot{1, std::vector<long>(64, 1)}));
  while (reads.load() < 100) std::this_thread::yield();
  for (long id = 2; id <= kPublications; ++id) {
    slots.publish(std::make_unique<const Snapshot>(Snapshot{id, std::vector<long>(64, id)}));
    if (id % 16 == 0) std::this_thread::yield();
  }
  done.store(true);
  r1.join();
  r2.join();
  EXPECT_EQ(torn.load(), 0);
  EXPECT_EQ(backwards.load(), 0);
  const executor::detail::SnapshotSlots<Snapshot>::Reader r(slots);
  ASSERT_NE(r.get(), nullptr);
  EXPECT_EQ(r.get()->id, kPublications);
}

}  // namespace
}  // namespace rbsf::controller
