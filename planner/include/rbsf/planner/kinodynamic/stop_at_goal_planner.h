#pragma once
/// \file
/// \brief An OMPL planner that stops as soon as the goal is reached, whatever the caller's
///        termination condition: rbsf's search ends at the first exact solution.
///
/// Some OMPL control planners (SST) keep improving a solution until their termination
/// condition says stop; ompl::tools::Benchmark's condition is the time limit only. Wrapped
/// in this planner they stop at the first state that satisfies the goal (the goal's least
/// distance <= 1, as ReorientationPlanner::solve() stops), so the benchmark's time is the
/// time to the first solution for every planner, the time plan-reorientation takes.
/// Name, parameters (Planner Arena's plannerConfigs), specs, progress properties and
/// planner data are the wrapped planner's.

#include <ompl/base/Planner.h>

#include "rbsf/planner/kinodynamic/goal.h"

namespace rbsf::planner {

/// \brief Forwards to `inner`, adding "goal reached" to the termination condition.
class StopAtGoalPlanner : public ompl::base::Planner {
 public:
  StopAtGoalPlanner(ompl::base::PlannerPtr inner, std::shared_ptr<const PoseGoal> goal);

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void setProblemDefinition(const ompl::base::ProblemDefinitionPtr& pdef) override;
  void clear() override;
  void setup() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;
  void printProperties(std::ostream& out) const override { inner_->printProperties(out); }
  void printSettings(std::ostream& out) const override { inner_->printSettings(out); }

  const ompl::base::PlannerPtr& inner() const { return inner_; }

 private:
  ompl::base::PlannerPtr inner_;
  std::shared_ptr<const PoseGoal> goal_;
};

}  // namespace rbsf::planner
