#pragma once
/// \file
/// \brief The planner's OMPL setup for one problem, as an ompl::control::SimpleSetup that
///        ReorientationPlanner::solve() and the benchmark tool (rbsf-bench, on
///        ompl::tools::Benchmark) both run.
///
/// What it holds (reorientation_planner.h describes each choice):
///   - state space SimStateSpace with the (phi, theta) projection;
///   - control space tau in R^(m+1) within the cell's limits, controls from
///     PhaseControlSampler;
///   - propagator SimPropagator (steps_per_control simulator steps per propagation step,
///     min..max_control_steps per control), validity SupportValidityChecker;
///   - start: the checked start configuration at rest; goal PoseGoal;
///   - the planner (KinodynamicPlanner) inside a StopAtGoalPlanner (the search ends
///     at the first exact solution, whoever's termination condition runs it), set on the
///     SimpleSetup.
/// The setup refers to the ReorientationPlanner's model and simulator: the planner must
/// outlive it. It does not seed OMPL's random numbers (ompl::RNG::setSeed is global and
/// must come before the first RNG is created: the caller does it).

#include <memory>
#include <string>

#include <ompl/base/Planner.h>
#include <ompl/control/SimpleSetup.h>

#include "rbsf/planner/kinodynamic/goal.h"
#include "rbsf/planner/kinodynamic/propagator.h"
#include "rbsf/planner/kinodynamic/validity.h"

namespace rbsf::planner {

/// \brief The OMPL objects of one planning problem.
struct PlannerSetup {
  std::shared_ptr<ompl::control::SimpleSetup> simple_setup;  ///< space, si, pdef, planner
  std::shared_ptr<SimStateSpace> space;
  std::shared_ptr<SimPropagator> propagator;  ///< counts propagations and simulator steps
  std::shared_ptr<SupportValidityChecker> checker;
  std::shared_ptr<PoseGoal> goal;  ///< records the least goal distance seen
  VecQ q0;                         ///< start configuration (part at rest)
};

/// \brief OMPL's control planner `planner` with its goal bias set.
ompl::base::PlannerPtr makeControlPlanner(KinodynamicPlanner planner,
                                          const ompl::control::SpaceInformationPtr& si,
                                          double goal_bias);

}  // namespace rbsf::planner
