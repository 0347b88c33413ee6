#include "rbsf/planner/pipeline/support_ompl_planner.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/Console.h>

#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/planner/kinodynamic/goal.h"
#include "rbsf/planner/kinodynamic/propagator.h"
#include "rbsf/planner/kinodynamic/state_space.h"

namespace rbsf::planner {

namespace ob = ompl::base;
namespace oc = ompl::control;

SupportOmplPlanner::SupportOmplPlanner(const oc::SpaceInformationPtr& si, const RbsfModel& model,
                                       SupportPlannerSettings settings)
    : ob::Planner(si, "Support"), siC_(si.get()), model_(model), settings_(std::move(settings)) {
  specs_.approximateSolutions = true;
  specs_.directed = true;
  params().declareParam<long>(
      "max_expansions", [this](long v) { settings_.max_expansions = v; },
      [this] { return settings_.max_expansions; });
  params().declareParam<int>(
      "max_paths", [this](int v) { settings_.max_paths = v; },
      [this] { return settings_.max_paths; });
}

void SupportOmplPlanner::setup() {
  ob::Planner::setup();
  const double period = kControlSteps * settings_.simulator.time_step;
  if (std::abs(siC_->getPropagationStepSize() - period) > 1e-12) {
    OMPL_ERROR("%s: the propagation step is %g s, a support plan's control lasts %g s",
               getName().c_str(), siC_->getPropagationStepSize(), period);
    setup_ = false;
  }
  const auto* propagator = dynamic_cast<const SimPropagator*>(siC_->getStatePropagator().get());
  if (propagator == nullptr || propagator->rule().enabled) {
    OMPL_ERROR("%s: the state propagator must be a SimPropagator without the decisive-modes rule",
               getName().c_str());
    setup_ = false;
  }
  if (pdef_ && !std::dynamic_pointer_cast<PoseGoal>(pdef_->getGoal())) {
    OMPL_ERROR("%s: the goal is not a PoseGoal", getName().c_str());
    setup_ = false;
  }
}

void SupportOmplPlanner::clear() {
  ob::Planner::clear();
  plan_ = plan::Plan{};
  expansions_ = 0;
  reach_ = SupportReach{};
  margins_ = plan::PlanMargins{};
}

ob::PlannerStatus SupportOmplPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  checkValidity();
  const auto goal = std::dynamic_pointer_cast<PoseGoal>(pdef_->getGoal());
  if (!goal) return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
  const ob::State* start = pis_.nextStart();
  if (start == nullptr) return ob::PlannerStatus::INVALID_START;
  const auto* space = si_->getStateSpace()->as<SimStateSpace>();
  const VecQ q0 = space->q(start);
  Problem problem;
  problem.start = Pose{q0[layout::kX], q0[layout::kY], q0[layout::kPhi]};
  problem.start_theta = q0[layout::kTheta];
  problem.goal = goal->pose();
  problem.absolute_angle = goal->absoluteAngle();
  problem.tolerance = {goal->positionTolerance(), goal->angleTolerance()};

  // SupportPlanner stops on a flag; OMPL's condition is polled beside it and sets the flag.
  SupportPlannerSettings s = settings_;
  s.time_limit = std::numeric_limits<double>::infinity();
  std::atomic<bool> stop{false}, done{false};
  std::thread watcher([&] {
    while (!done.load()) {
      if (ptc()) {
        stop.store(true);
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  SupportPlanner support(model_, s);
  plan::Plan plan;
  const bool found = support.solve(problem, plan, &stop);
  done.store(true);
  watcher.join();
  expansions_ = support.expansions();
  reach_ = support.reach();
  margins_ = support.margins();
  if (!found) {
    OMPL_INFORM("%s: %s", getName().c_str(), support.message().c_str());
    const bool budget = s.max_expansions > 0 && expansions_ >= s.max_expansions;
    return stop.load() || budget ? ob::PlannerStatus::TIMEOUT : ob::PlannerStatus::ABORT;
  }
  plan_ = plan;

  // The path: each segment's tau held for its steps, propagated from the start.
  auto path = std::make_shared<oc::PathControl>(si_);
  ob::State* from = si_->allocState();
  ob::State* to = si_->allocState();
  oc::Control* control = siC_->allocControl();
  // The plan's own start configuration: the part and the base as in `start`, the fingers
  // its first support lifts at their lower stroke limits.
  space->fromSim(SimState(plan.q0, VecQ::Zero(plan.q0.size())), from);
  path->append(from);
  double* u = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  for (const plan::PlanSegment& seg : plan.segments) {
    for (int j = 0; j < seg.tau.size(); ++j) u[j] = seg.tau[j];
    const int steps = std::max(1, static_cast<int>(std::lround(double(seg.steps) / kControlSteps)));
    siC_->propagate(from, control, steps, to);
    path->append(to, control, steps * siC_->getPropagationStepSize());
    std::swap(from, to);
  }
  double distance = 0.0;
  goal->isSatisfied(from, &distance);  // also records the best distance, as other planners do
  si_->freeState(from);
  si_->freeState(to);
  siC_->freeControl(control);
  const bool exact = plan.status == plan::PlanStatus::kExact;
  pdef_->addSolutionPath(path, !exact, exact ? 0.0 : distance, getName());
  return exact ? ob::PlannerStatus::EXACT_SOLUTION : ob::PlannerStatus::APPROXIMATE_SOLUTION;
}

}  // namespace rbsf::planner
