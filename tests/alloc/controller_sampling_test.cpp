// The controller facade's real-time path allocates nothing: sample(), track() (with and
// without its status, through non-finite readings) and addPartPose() on a published plan,
// for times before, inside and after the plan; hold(), heldState() and start().
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "malloc_counter.h"
#include "rbsf/controller/reorientation_controller.h"

namespace rbsf {
namespace {

TEST(NoAllocationController, SampleTrackAndPartPoses) {
  if (!test::mallocCountingAvailable()) GTEST_SKIP() << "malloc not countable in this build";
  controller::ReorientationController c(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml");
  controller::ReorientationRequest request;
  request.problem.start = {0.1, 0.40, 0.0};
  request.problem.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
  request.planner.seed = 4;
  request.planner.time_limit = 120.0;
  request.certificate.trials = 2;
  request.accept_uncertified = true;
  ASSERT_TRUE(c.plan(request));
  c.wait();  // the worker is done: only this thread runs while counting
  ASSERT_EQ(c.status(), controller::ControllerStatus::kReady) << c.result().message;
  double duration = 0.0;
  VecQ q0;
  ASSERT_TRUE(c.publishedPlan(duration, q0));
  ReferenceSample ref;
  VecU tau, joints(c.model().controlDim());
  for (int j = 0; j < joints.size(); ++j) joints[j] = q0[3 + j];
  c.track(0.0, joints, tau);  // the law starts (its first call, as a loop's)
  std::uint64_t id = 0;
  int sampled = 0;
  ExecutionStatus status;
  Pose held;
  double theta = 0.0;
  VecU bad = joints;
  bad[1] = std::nan("");
  test::MallocCounter counter;
  for (int k = 1; k < 1200; ++k) {
    const double t = 1e-3 * k * duration;  // 0 .. 1.2 T
    sampled += c.sample(t, ref, &id);
    if (k % 10 == 0) c.addPartPose(t, Pose{ref.q[0], ref.q[1], ref.q[2]});
    if (k % 97 == 0) c.addPartPose(t, Pose{std::nan(""), ref.q[1], ref.q[2]});
    if (k % 2 == 0)
      sampled += c.track(t, joints, tau, &id);
    else
      sampled += c.track(t, k % 50 == 1 ? bad : joints, tau, status, &id);
    if (k == 900) c.hold();
    if (k > 900) sampled += c.heldState(held, theta);
  }
  c.start();
  sampled += c.track(0.0, joints, tau, status, &id);
  EXPECT_EQ(counter.count(), 0);
  EXPECT_EQ(status.verdict == ExecutionVerdict::kHolding, false);
  EXPECT_EQ(sampled, 2398 + 299 + 1);
  EXPECT_EQ(id, 1u);
}

}  // namespace
}  // namespace rbsf
