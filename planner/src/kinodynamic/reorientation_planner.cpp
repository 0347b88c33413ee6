#include "rbsf/planner/kinodynamic/reorientation_planner.h"

#include "rbsf/dynamics/control/feedback_schedule.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/SpaceInformation.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/planner/kinodynamic/goal.h"
#include "rbsf/planner/kinodynamic/projection.h"
#include "rbsf/planner/kinodynamic/stop_at_goal_planner.h"

namespace rbsf::planner {

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace {

std::string poseText(const Pose& p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g deg)", p.x, p.y, p.phi * 180.0 / M_PI);
  return buf;
}

}  // namespace

ReorientationPlanner::ReorientationPlanner(const RbsfModel& model, PlannerSettings settings)
    : model_(model), settings_(std::move(settings)), simulator_(model, settings_.simulator) {
  checkSettings(settings_);
}

VecQ ReorientationPlanner::checkProblem(const Problem& problem) const {
  checkTolerance(problem.tolerance);
  const Cell& cell = model_.cell();
  if (problem.start_theta < cell.base.theta_min || problem.start_theta > cell.base.theta_max)
    throw InputError("--start-theta is outside the base range");
  const Placement start = placeFingers(model_, problem.start, problem.start_theta);
  if (!start.ok)
    throw InputError("the fingers cannot hold the start pose " + poseText(problem.start) + ": " +
                     start.message);
  VecQ q(model_.configDim());
  q << problem.start.x, problem.start.y, problem.start.phi, problem.start_theta,
      start.strokes.head(model_.numFingers());
  ModelData data(model_.numFingers());
  model_.updateContacts(q, data);
  if (!holdingTorques(model_, q, data).feasible)
    throw InputError("the fingers cannot hold the part at rest at the start pose " +
                     poseText(problem.start) +
                     ": no contact forces in the friction cones balance it within the limits");
  // The goal: some base angle at which at least min_touching fingers reach the part
  // (the tip's line of travel enters it within the stroke), the validity's support test.
  const int n = 181;
  int most = 0;
  for (int k = 0; k < n; ++k) {
    const double theta =
        cell.base.theta_min + (cell.base.theta_max - cell.base.theta_min) * k / (n - 1);
    const Vec2 x_o(problem.goal.x, problem.goal.y);
    const Vec2 dir = rotate(-problem.goal.phi, rotate(theta, Vec2(0.0, 1.0)));
    int reach = 0;
    for (const FingerParams& f : cell.fingers) {
      const Vec2 origin = rotate(-problem.goal.phi, rotate(theta, Vec2(f.r, 0.0)) - x_o);
      double l = 0.0, xi = 0.0;
      if (model_.shape().entryAlongLine(origin, dir, l, xi) && l >= f.stroke_min &&
          l <= f.stroke_max)
        ++reach;
    }
    most = std::max(most, reach);
    if (reach >= settings_.validity.min_touching) return q;
  }
  std::string why = "the goal pose " + poseText(problem.goal) + " is out of reach: ";
  if (most == 0) {
    why += "no finger";
  } else {
    why += "only ";
    why += std::to_string(most);
    why += " finger(s)";
  }
  why += " can reach the part at any base angle in the base range (";
  why += std::to_string(settings_.validity.min_touching);
  why += " needed to support it)";
  throw InputError(why);
}

PlannerSetup ReorientationPlanner::setup(const Problem& problem) const {
  PlannerSetup out;
  out.q0 = checkProblem(problem);
  const PlannerSettings& s = settings_;
  const int m = model_.numFingers();
  const double dt = simulator_.settings().time_step;
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);

  out.space = std::make_shared<SimStateSpace>(model_, s.speed);
  out.space->registerDefaultProjection(
      std::make_shared<PhiThetaProjection>(out.space.get(), s.projection_cell, s.projection_cell));
  auto cspace = std::make_shared<oc::RealVectorControlSpace>(out.space, model_.controlDim());
  ob::RealVectorBounds cb(model_.controlDim());
  const Cell& cell = model_.cell();
  cb.setLow(layout::kTauTheta, -cell.base.torque_limit);
  cb.setHigh(layout::kTauTheta, cell.base.torque_limit);
  for (int i = 0; i < m; ++i) {
    cb.setLow(layout::fingerForce(i), -cell.fingers[i].force_limit);
    cb.setHigh(layout::fingerForce(i), cell.fingers[i].force_limit);
  }
  cspace->setBounds(cb);
  // The sampler refers to the space and the settings, which outlive it (the setup holds
  // the space; the settings belong to this planner).
  const SimStateSpace* sp = out.space.get();
  const RbsfModel* model = &model_;
  const PlannerSettings* ps = &settings_;
  cspace->setControlSamplerAllocator([model, sp, ps](const oc::ControlSpace* cs) {
    return std::make_shared<PhaseControlSampler>(cs, *model, *sp, ps->sampler,
                                                 ps->validity.touch_distance);
  });
  auto si = std::make_shared<oc::SpaceInformation>(out.space, cspace);
  out.checker = std::make_shared<SupportValidityChecker>(si, model_, s.validity);
  si->setStateValidityChecker(out.checker);
  out.propagator =
      std::make_shared<SimPropagator>(si, simulator_, *out.space, s.decisive_modes,
                                      s.keep_motion_limits ? &cell.motion_limits : nullptr);
  si->setStatePropagator(out.propagator);
  si->setPropagationStepSize(s.steps_per_control * dt);
  si->setMinMaxControlDuration(s.min_control_steps, s.max_control_steps);
  si->setup();

  out.simple_setup = std::make_shared<oc::SimpleSetup>(si);
  ob::State* start = si->allocState();
  out.space->fromSim(SimState(out.q0, VecQ::Zero(out.q0.size())), start);
  out.simple_setup->getProblemDefinition()->addStartState(start);
  si->freeState(start);
  out.goal =
      std::make_shared<PoseGoal>(si, problem.goal, problem.tolerance.position,
                                 problem.tolerance.angle, *out.checker, problem.absolute_angle);
  out.simple_setup->setGoal(out.goal);
  out.simple_setup->setPlanner(std::make_shared<StopAtGoalPlanner>(
      makeControlPlanner(s.planner, si, s.goal_bias), out.goal));
  return out;
}

bool ReorientationPlanner::solve(const Problem& problem, plan::Plan& plan,
                                 const SearchContext& context) {
  const PlannerSettings& s = settings_;
  ompl::RNG::setSeed(s.seed == 0 ? 1 : s.seed);
  const PlannerSetup setup = this->setup(problem);
  setup.simple_setup->setup();
  const SimPropagator& propagator = *setup.propagator;
  const PoseGoal& goal = *setup.goal;

  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  double last_report = 0.0;
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  const ob::PlannerTerminationCondition ptc([&] {
    const double t = elapsed();
    if (context.progress && t - last_report >= 1.0) {
      last_report = t;
      context.progress({t, propagator.propagations(), goal.bestDistance()});
    }
    const bool cancelled = context.cancelled();
    const bool spent = s.max_propagations > 0 && propagator.propagations() >= s.max_propagations;
    return cancelled || spent || t >= s.time_limit;  // the goal stops it too (StopAtGoalPlanner)
  });
  setup.simple_setup->getPlanner()->solve(ptc);
  const double planning_time = elapsed();
  best_distance_ = goal.bestDistance();
  propagations_ = propagator.propagations();
  return makePlan(problem, setup, planning_time, plan);
}

bool ReorientationPlanner::makePlan(const Problem& problem, const PlannerSetup& setup,
                                    double planning_time, plan::Plan& plan) const {
  const PlannerSettings& s = settings_;
  const ob::ProblemDefinitionPtr& pdef = setup.simple_setup->getProblemDefinition();
  const ob::PathPtr path = pdef->getSolutionPath();
  if (!path) return false;
  const double dt = simulator_.settings().time_step;
  const VecQ& q0 = setup.q0;
  auto& pc = static_cast<oc::PathControl&>(*path);
  plan = plan::Plan();
  plan.status =
      pdef->hasExactSolution() ? plan::PlanStatus::kExact : plan::PlanStatus::kApproximate;
  plan.planner = toString(s.planner);
  plan.seed = s.seed;
  plan.planning_time = planning_time;
  plan.propagations = setup.propagator->propagations();
  plan.simulator = s.simulator;
  plan.steps_per_control = s.steps_per_control;
  plan.start = problem.start;
  plan.start_theta = problem.start_theta;
  plan.goal = problem.goal;
  plan.q0 = q0;
  for (std::size_t k = 0; k < pc.getControlCount(); ++k) {
    plan::PlanSegment seg;
    seg.steps = static_cast<int>(std::lround(pc.getControlDuration(k) / dt));
    seg.duration = seg.steps * dt;
    const double* u = pc.getControl(k)->as<oc::RealVectorControlSpace::ControlType>()->values;
    seg.tau = VecU(model_.controlDim());
    for (int j = 0; j < model_.controlDim(); ++j) seg.tau[j] = u[j];
    if (seg.steps > 0) plan.segments.push_back(std::move(seg));
  }
  std::vector<SimState> ends;
  // Contacts pressed by less than the law's min_normal_force share of the weight are free.
  const Cell& cell = model_.cell();
  const double light =
      FeedbackSettings{}.contacts.min_normal_force * cell.object.mass * cell.gravity;
  plan.samples = simulateSegments(simulator_, q0, plan.segments, s.sample_steps, &ends, light);
  // The re-simulation against the planner's own states at the segment ends.
  std::size_t e = 0;
  for (std::size_t k = 0; k < pc.getControlCount() && e < ends.size(); ++k) {
    if (std::lround(pc.getControlDuration(k) / dt) == 0) continue;
    const auto* st = pc.getState(k + 1)->as<SimStateSpace::StateType>();
    const double dq = (st->sim->q - ends[e].q).cwiseAbs().maxCoeff();
    const double dv = (st->sim->v - ends[e].v).cwiseAbs().maxCoeff();
    plan.path_mismatch = std::max({plan.path_mismatch, dq, dv});
    ++e;
  }
  const VecQ& qf = ends.empty() ? q0 : ends.back().q;
  plan.goal_distance = std::max(
      std::hypot(qf[layout::kX] - problem.goal.x, qf[layout::kY] - problem.goal.y) /
          problem.tolerance.position,
      std::abs(goalAngleError(qf[layout::kPhi], problem.goal.phi, problem.absolute_angle)) /
          problem.tolerance.angle);
  return true;
}

}  // namespace rbsf::planner
