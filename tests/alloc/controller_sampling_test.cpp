// The controller facade's real-time path allocates nothing: sample() and computeTorque()
// on a published plan, for times before, inside and after the plan.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "malloc_counter.h"
#include "rbsf/controller/reorientation_controller.h"

namespace rbsf {
namespace {

TEST(NoAllocationController, SampleAndComputeTorque) {
  if (!test::mallocCountingAvailable()) GTEST_SKIP() << "malloc not countable in this build";
  controller::ReorientationController c(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml");
  controller::ReorientationRequest request;
  request.problem.start = {0.1, 0.40, 0.0};
  request.problem.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
  request.planner.seed = 7;
  request.planner.time_limit = 120.0;
  ASSERT_TRUE(c.plan(request));
  c.wait();  // the worker is done: only this thread runs while counting
  ASSERT_EQ(c.status(), controller::ControllerStatus::kReady) << c.result().message;
  double duration = 0.0;
  VecQ q0;
  ASSERT_TRUE(c.publishedPlan(duration, q0));
  ReferenceSample ref;
  VecU tau;
  c.computeTorque(0.0, q0, VecQ::Zero(q0.size()), tau, ref);  // size the outputs once
  const VecQ v = VecQ::Constant(q0.size(), 0.01);
  std::uint64_t id = 0;
  int sampled = 0;
  test::MallocCounter counter;
  for (int k = -100; k < 1100; ++k) {
    const double t = 1e-3 * k * duration;  // -0.1 T .. 1.1 T
    sampled += c.sample(t, ref, &id);
    sampled += c.computeTorque(t, ref.q, v, tau, ref, &id);
  }
  EXPECT_EQ(counter.count(), 0);
  EXPECT_EQ(sampled, 2400);
  EXPECT_EQ(id, 1u);
}

}  // namespace
}  // namespace rbsf
