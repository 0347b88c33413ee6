// The support planner behind OMPL's interface (support_ompl_planner.h): run through an
// ompl::control::SimpleSetup like KPIECE1, it returns OMPL's statuses (exact, timeout,
// abort) and an exact solution path whose controls, re-propagated by the setup's propagator,
// end on the goal as the support plan does.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/control/PathControl.h>
#include <ompl/util/Console.h>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"
#include "rbsf/planner/pipeline/support_ompl_planner.h"

namespace rbsf::planner {
namespace {

namespace ob = ompl::base;
namespace oc = ompl::control;

const RbsfModel& defaultModel() {
  static const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  return model;
}

Problem turn(double degrees) {
  Problem p;
  p.start = Pose{0.1, 0.40, 0.0};
  p.goal = Pose{0.1, 0.40, degrees * M_PI / 180};
  return p;
}

/// The benchmark's setup with the support planner on it: the propagation step a support plan's
/// control period, the propagator without the decisive-modes rule (as rbsf-bench sets them).
struct SupportSetup {
  SupportSetup(const Problem& problem, int steps_per_control, bool decisive_modes = false)
      : rp(defaultModel(),
           [&] {
             PlannerSettings s;
             s.steps_per_control = steps_per_control;
             s.decisive_modes.enabled = decisive_modes;
             return s;
           }()),
        setup(rp.setup(problem)) {
    planner = std::make_shared<SupportOmplPlanner>(setup.simple_setup->getSpaceInformation(),
                                                   defaultModel());
    setup.simple_setup->setPlanner(planner);
  }
  ReorientationPlanner rp;
  PlannerSetup setup;
  std::shared_ptr<SupportOmplPlanner> planner;
};

TEST(SupportOmplPlanner, AnExactSolutionPathReplaysThePlanOntoTheGoal) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  SupportSetup s(turn(-15.0), SupportOmplPlanner::kControlSteps);
  s.planner->settings().max_expansions = 20000;
  const ob::PlannerStatus status =
      s.setup.simple_setup->solve(ob::plannerNonTerminatingCondition());
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << status.asString();
  const plan::Plan& plan = s.planner->lastPlan();
  EXPECT_EQ(plan.planner, "support");
  auto& path = static_cast<oc::PathControl&>(
      *s.setup.simple_setup->getProblemDefinition()->getSolutionPath());
  ASSERT_EQ(path.getControlCount(), plan.segments.size());
  // The path's states are the propagator's from the plan's start configuration (the part's
  // pose and the base angle of the problem's start); they follow the plan to its end.
  const VecQ first = s.setup.space->q(path.getState(0));
  EXPECT_EQ(first, plan.q0);
  EXPECT_EQ(first.head<4>(), s.setup.q0.head<4>());
  const VecQ end = s.setup.space->q(path.getState(path.getStateCount() - 1));
  const VecQ planned = plan.samples.back().q;
  EXPECT_LT((end - planned).norm(), 1e-6) << end.transpose() << "\n" << planned.transpose();
  EXPECT_TRUE(s.setup.goal->isSatisfied(path.getState(path.getStateCount() - 1)));
  EXPECT_GT(s.planner->expansions(), 0);
  // clear() forgets the plan, as OMPL's Benchmark expects between runs.
  s.planner->clear();
  EXPECT_TRUE(s.planner->lastPlan().segments.empty());
}

TEST(SupportOmplPlanner, StatusesForATurnWithoutAPathAndAnotherPropagationStep) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  {  // +15 degrees: the searches are exhausted (the reach is measured), or stopped at once.
    SupportSetup s(turn(15.0), SupportOmplPlanner::kControlSteps);
    const ob::PlannerStatus stopped =
        s.setup.simple_setup->solve(ob::PlannerTerminationCondition([] { return true; }));
    EXPECT_EQ(stopped, ob::PlannerStatus::TIMEOUT) << stopped.asString();
    s.planner->clear();
    s.setup.simple_setup->getProblemDefinition()->clearSolutionPaths();
    const ob::PlannerStatus out = s.setup.simple_setup->solve(ob::plannerNonTerminatingCondition());
    EXPECT_EQ(out, ob::PlannerStatus::ABORT) << out.asString();
    EXPECT_TRUE(s.planner->reach().measured);
  }
  // The kinodynamic planner's 20-step propagation cannot hold a support plan's controls, and
  // its decisive-modes rule would cut them short: either setup is refused.
  for (const auto& [steps, decisive] : {std::pair{20, false}, std::pair{5, true}}) {
    SupportSetup wrong(turn(-15.0), steps, decisive);
    wrong.planner->setProblemDefinition(wrong.setup.simple_setup->getProblemDefinition());
    wrong.planner->setup();
    EXPECT_FALSE(wrong.planner->isSetup()) << steps << " " << decisive;
  }
  SupportSetup right(turn(-15.0), SupportOmplPlanner::kControlSteps);
  right.planner->setProblemDefinition(right.setup.simple_setup->getProblemDefinition());
  right.planner->setup();
  EXPECT_TRUE(right.planner->isSetup());
}

}  // namespace
}  // namespace rbsf::planner
