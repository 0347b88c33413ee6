#include "rbsf/planner/kinodynamic/planner_setup.h"

#include <ompl/control/planners/est/EST.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/pdst/PDST.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/planners/sst/SST.h>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::planner {

namespace oc = ompl::control;

namespace {

template <class P>
ompl::base::PlannerPtr withGoalBias(const oc::SpaceInformationPtr& si, double goal_bias) {
  auto p = std::make_shared<P>(si);
  p->setGoalBias(goal_bias);
  return p;
}

}  // namespace

ompl::base::PlannerPtr makeControlPlanner(KinodynamicPlanner planner,
                                          const oc::SpaceInformationPtr& si, double goal_bias) {
  switch (planner) {
    case KinodynamicPlanner::kKPIECE1:
      return withGoalBias<oc::KPIECE1>(si, goal_bias);
    case KinodynamicPlanner::kRRT:
      return withGoalBias<oc::RRT>(si, goal_bias);
    case KinodynamicPlanner::kSST:
      return withGoalBias<oc::SST>(si, goal_bias);
    case KinodynamicPlanner::kEST:
      return withGoalBias<oc::EST>(si, goal_bias);
    case KinodynamicPlanner::kPDST:
      return withGoalBias<oc::PDST>(si, goal_bias);
  }
  throw InputError("unknown planner (choose KPIECE1, RRT, SST, EST or PDST)");
}

}  // namespace rbsf::planner
