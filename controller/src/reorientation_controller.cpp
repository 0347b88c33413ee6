#include "rbsf/controller/reorientation_controller.h"

#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "rbsf/dynamics/errors.h"
#include "rbsf/planner/plan_reference.h"
#include "rbsf/planner/plan_replay.h"
#ifdef RBSF_CONTROLLER_WITH_TRAJOPT
#include "rbsf/trajopt/plan_refinement.h"
#endif
#include "snapshot_slots.h"

namespace rbsf::controller {

const char* toString(ControllerStatus status) {
  switch (status) {
    case ControllerStatus::kIdle:
      return "idle";
    case ControllerStatus::kPlanning:
      return "planning";
    case ControllerStatus::kReady:
      return "ready";
    case ControllerStatus::kFailed:
      return "failed";
  }
  return "?";
}

const char* toString(PlanOutcome outcome) {
  switch (outcome) {
    case PlanOutcome::kNone:
      return "none";
    case PlanOutcome::kExact:
      return "exact";
    case PlanOutcome::kOptimized:
      return "optimized";
    case PlanOutcome::kApproximate:
      return "approximate";
    case PlanOutcome::kNoPath:
      return "no path";
    case PlanOutcome::kCancelled:
      return "cancelled";
    case PlanOutcome::kInputError:
      return "input error";
    case PlanOutcome::kError:
      return "error";
  }
  return "?";
}

namespace {

/// \brief What a real-time reader sees: one plan's reference and its tracking controller.
struct PublishedPlan {
  PublishedPlan(std::uint64_t id_, const RbsfModel& model, const planner::Plan& plan,
                const TrackingSettings& tracking_settings)
      : id(id_),
        duration(plan.duration()),
        time_step(plan.simulator.time_step),
        q0(plan.q0),
        reference(planner::makeReference(plan)),
        tracking(model, plan.q0, tracking_settings) {}

  std::uint64_t id;
  double duration;
  double time_step;  // h of the plan's simulator: the control period computeTorque assumes
  VecQ q0;
  ReferenceTrajectory reference;
  TrackingController tracking;
};

}  // namespace

struct ReorientationController::Impl {
  Impl(Cell cell, const TrackingSettings& tracking_settings)
      : model(std::move(cell)), tracking(tracking_settings) {}

  void run(ReorientationRequest request);
  void finish(PlanOutcome outcome, std::string message, planner::Plan plan, double best,
              bool publish_it);

  const RbsfModel model;
  const TrackingSettings tracking;
  detail::SnapshotSlots<PublishedPlan> slots;
  std::atomic<ControllerStatus> status{ControllerStatus::kIdle};
  std::atomic<PlanOutcome> outcome{PlanOutcome::kNone};
  std::atomic<bool> cancel{false};
  std::uint64_t next_id = 1;  // worker only (one at a time)

  std::mutex mutex;  // guards worker (the handle) and result; never taken by a sampler
  std::thread worker;
  RequestResult result;
};

void ReorientationController::Impl::finish(PlanOutcome how, std::string message, planner::Plan plan,
                                           double best, bool publish_it) {
  std::uint64_t id = 0;
  if (publish_it) {
    id = next_id++;
    slots.publish(std::make_unique<const PublishedPlan>(id, model, plan, tracking));
  }
  {
    const std::lock_guard<std::mutex> lock(mutex);
    result.outcome = how;
    result.message = std::move(message);
    result.plan = std::move(plan);
    result.best_distance = best;
    result.plan_id = id;
  }
  outcome.store(how);
  status.store(publish_it ? ControllerStatus::kReady : ControllerStatus::kFailed);
}

void ReorientationController::Impl::run(ReorientationRequest request) {
  double best = 0.0;
  try {
    planner::PlannerSettings settings = request.planner;
    settings.cancel = &cancel;
    settings.progress = std::move(request.progress);
    planner::ReorientationPlanner search(model, std::move(settings));
    planner::Plan plan;
    const bool found = search.solve(request.problem, plan);
    best = search.bestDistance();
    if (cancel.load()) {
      finish(PlanOutcome::kCancelled,
             "cancelled after " + std::to_string(plan.planning_time) + " s", std::move(plan), best,
             false);
      return;
    }
    if (!found) {
      finish(PlanOutcome::kNoPath, "the planner produced no path", {}, best, false);
      return;
    }
    if (plan.status != "exact") {
      const bool accept = request.accept_approximate;
      finish(PlanOutcome::kApproximate,
             "time limit: closest approach " + std::to_string(best) + " tolerance units",
             std::move(plan), best, accept);
      return;
    }
    std::string note;
    PlanOutcome how = PlanOutcome::kExact;
    if (request.optimize) {
#ifdef RBSF_CONTROLLER_WITH_TRAJOPT
      trajopt::OptimizerSettings opt = request.optimizer;
      opt.cancel = &cancel;
      const trajopt::PlanOptimizer optimizer(model, opt);
      // The acceptance rule of plan-reorientation (plan_replay.h): the closed-loop replay
      // with this controller's tracking gains must reach the goal in the planned phases.
      const Simulator simulator(model, request.planner.simulator);
      planner::ReplaySettings replay;
      replay.position_tolerance = request.planner.position_tolerance;
      replay.angle_tolerance = request.planner.angle_tolerance;
      replay.tracking = tracking;
      trajopt::RefineOutcome refined = trajopt::refinePlan(optimizer, simulator, plan, replay);
      if (cancel.load()) {
        finish(PlanOutcome::kCancelled, "cancelled while optimising", std::move(plan), best, false);
        return;
      }
      if (refined.accepted) how = PlanOutcome::kOptimized;
      note = std::move(refined.reason);
      plan = std::move(refined.plan);
#else
      note = "optimisation not used: rbsf was built without rbsf::trajopt";
#endif
    }
    finish(how, std::move(note), std::move(plan), best, true);
  } catch (const InputError& e) {
    finish(PlanOutcome::kInputError, e.what(), {}, best, false);
  } catch (const std::exception& e) {
    finish(PlanOutcome::kError, e.what(), {}, best, false);
  }
}

ReorientationController::ReorientationController(const std::string& cell_file,
                                                 const TrackingSettings& tracking)
    : ReorientationController(loadCell(cell_file), tracking) {}

ReorientationController::ReorientationController(Cell cell, const TrackingSettings& tracking)
    : impl_(std::make_unique<Impl>(std::move(cell), tracking)) {}

ReorientationController::~ReorientationController() {
  cancel();
  wait();
}

const RbsfModel& ReorientationController::model() const { return impl_->model; }

bool ReorientationController::plan(const ReorientationRequest& request) {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  if (impl_->status.load() == ControllerStatus::kPlanning) return false;
  if (impl_->worker.joinable()) impl_->worker.join();  // finished: returns at once
  impl_->cancel.store(false);
  impl_->status.store(ControllerStatus::kPlanning);
  impl_->worker =
      std::thread([impl = impl_.get(), request]() mutable { impl->run(std::move(request)); });
  return true;
}

void ReorientationController::cancel() noexcept { impl_->cancel.store(true); }

void ReorientationController::wait() {
  std::thread worker;
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    worker = std::move(impl_->worker);
  }
  if (worker.joinable()) worker.join();
}

ControllerStatus ReorientationController::status() const noexcept { return impl_->status.load(); }

PlanOutcome ReorientationController::outcome() const noexcept { return impl_->outcome.load(); }

RequestResult ReorientationController::result() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->result;
}

bool ReorientationController::sample(double t, ReferenceSample& out,
                                     std::uint64_t* plan_id) const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return false;
  p->reference.sample(t, out);
  if (plan_id != nullptr) *plan_id = p->id;
  return true;
}

bool ReorientationController::computeTorque(double t, const VecQ& q, const VecQ& v, VecU& tau,
                                            ReferenceSample& ref,
                                            std::uint64_t* plan_id) const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return false;
  p->reference.sample(t, ref);
  // The feed-forward of the control period [t, t + h): its midpoint's, so that a segment
  // starting at t is never missed by rounding of t (as planner::replayPlan does).
  ReferenceSample mid;  // fixed-capacity vectors: no allocation
  p->reference.sample(t + 0.5 * p->time_step, mid);
  ref.tau = mid.tau;
  ref.phase = mid.phase;
  p->tracking.compute(q, v, ref, tau);
  if (plan_id != nullptr) *plan_id = p->id;
  return true;
}

bool ReorientationController::publishedPlan(double& duration, VecQ& q0) const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return false;
  duration = p->duration;
  q0 = p->q0;
  return true;
}

std::uint64_t ReorientationController::planId() const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  return reader.get() == nullptr ? 0 : reader.get()->id;
}

}  // namespace rbsf::controller
