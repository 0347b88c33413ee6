#include "rbsf/planner/kinodynamic/stop_at_goal_planner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>

namespace rbsf::planner {

namespace ob = ompl::base;

StopAtGoalPlanner::StopAtGoalPlanner(ob::PlannerPtr inner, std::shared_ptr<const PoseGoal> goal)
    : ob::Planner(inner->getSpaceInformation(), inner->getName()),
      inner_(std::move(inner)),
      goal_(std::move(goal)) {
  specs_ = inner_->getSpecs();
  params_ = inner_->params();  // the parameters are bound to the inner planner's setters
  for (const auto& [name, fn] : inner_->getPlannerProgressProperties())
    addPlannerProgressProperty(name, fn);
}

ob::PlannerStatus StopAtGoalPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  const PoseGoal* goal = goal_.get();
  // Not bestDistance() <= 1: an unsupported state in the region (a part falling through the
  // goal pose) is no solution, and stopping there would return an approximate plan early.
  const ob::PlannerTerminationCondition reached([goal] { return goal->reached(); });
  return inner_->solve(ob::plannerOrTerminationCondition(ptc, reached));
}

void StopAtGoalPlanner::setProblemDefinition(const ob::ProblemDefinitionPtr& pdef) {
  ob::Planner::setProblemDefinition(pdef);
  inner_->setProblemDefinition(pdef);
}

void StopAtGoalPlanner::clear() {
  ob::Planner::clear();
  inner_->clear();
}

void StopAtGoalPlanner::setup() {
  ob::Planner::setup();
  inner_->setup();
}

void StopAtGoalPlanner::getPlannerData(ob::PlannerData& data) const {
  inner_->getPlannerData(data);
}

}  // namespace rbsf::planner
