// The planner's propagation (a hot path: every tree extension) allocates nothing, with the
// decisive-modes rule checking every step.
#include <gtest/gtest.h>

#include <string>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "malloc_counter.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"

namespace rbsf {
namespace {

TEST(NoAllocationPlanner, PropagateChecksEveryStepWithoutAllocating) {
  if (!test::mallocCountingAvailable()) GTEST_SKIP() << "malloc not countable in this build";
  const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  planner::PlannerSettings settings;
  const planner::ReorientationPlanner rp(model, settings);
  planner::Problem problem;
  problem.start = {0.1, 0.40, 0.0};
  problem.goal = {0.1, 0.40, -0.5};
  const planner::PlannerSetup setup = rp.setup(problem);
  const auto si = setup.simple_setup->getSpaceInformation();
  const int m = model.numFingers();
  ModelData d(m);
  model.updateContacts(setup.q0, d);
  const HoldingSolution hold = holdingTorques(model, setup.q0, d);
  ASSERT_TRUE(hold.feasible);
  ompl::base::State* state = si->allocState();
  ompl::base::State* next = si->allocState();
  ompl::control::Control* control = si->allocControl();
  double* u = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
  setup.space->fromSim(SimState(setup.q0, VecQ::Zero(m + 4)), state);
  const double step = settings.steps_per_control * settings.simulator.time_step;
  // Held, then the base pushed harder and harder: the rule passes steps and refuses some.
  for (int j = 0; j <= m; ++j) u[j] = hold.tau[j];
  setup.propagator->propagate(state, control, step, next);  // warm-up
  int refused = 0;
  test::MallocCounter counter;
  for (int k = 0; k < 200; ++k) {
    u[0] = hold.tau[0] + 2.0 * k;
    setup.propagator->propagate(state, control, step, next);
    refused += static_cast<planner::SimStateSpace::StateType*>(next)->decisive ? 0 : 1;
  }
  EXPECT_EQ(counter.count(), 0);
  EXPECT_GT(refused, 0);
  EXPECT_LT(refused, 200);
  si->freeControl(control);
  si->freeState(next);
  si->freeState(state);
}

TEST(NoAllocationPlanner, SamplerDrawsControlsWithoutAllocating) {
  // The control sampler runs at every tree extension, before the propagation: its phase
  // targets' inverse dynamics (phase_targets.h) must not touch the heap either.
  if (!test::mallocCountingAvailable()) GTEST_SKIP() << "malloc not countable in this build";
  const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  const planner::ReorientationPlanner rp(model, planner::PlannerSettings{});
  planner::Problem problem;
  problem.start = {0.1, 0.40, 0.0};
  problem.goal = {0.1, 0.40, -0.5};
  const planner::PlannerSetup setup = rp.setup(problem);
  setup.simple_setup->setup();
  const auto si = setup.simple_setup->getSpaceInformation();
  const int m = model.numFingers();
  ompl::base::State* state = si->allocState();
  ompl::control::Control* control = si->allocControl();
  setup.space->fromSim(SimState(setup.q0, VecQ::Zero(m + 4)), state);
  const ompl::control::ControlSamplerPtr sampler = si->allocControlSampler();
  sampler->sample(control, state);  // warm-up
  test::MallocCounter counter;
  for (int k = 0; k < 200; ++k) sampler->sample(control, state);
  EXPECT_EQ(counter.count(), 0);
  si->freeControl(control);
  si->freeState(state);
}

}  // namespace
}  // namespace rbsf
