#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/io/cell_file.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <variant>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/plan/plan_fit.h"
#include "rbsf/plan/plan_reference.h"

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
    case PlanOutcome::kLoaded:
      return "loaded";
    case PlanOutcome::kNotCertified:
      return "not certified";
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

struct ReorientationController::Impl {
  Impl(Cell cell, const FeedbackSettings& feedback_settings, const ExecutionLimits& limits)
      : runner(std::move(cell), feedback_settings, limits),
        model(runner.model()),
        feedback(feedback_settings) {}

  void run(ReorientationRequest request);
  void finish(PlanOutcome outcome, std::string message, plan::PlanRecord record, double best,
              bool publish_it);
  /// \brief The pipeline's settings of `request` on this cell, with the facade's feedback.
  planner::PipelineSettings pipelineSettings(const ReorientationRequest& request) const;

  executor::PlanRunner runner;  ///< the published plans and their execution
  const RbsfModel& model;
  const FeedbackSettings feedback;
  std::atomic<ControllerStatus> status{ControllerStatus::kIdle};
  std::atomic<PlanOutcome> outcome{PlanOutcome::kNone};
  std::atomic<bool> cancel{false};

  std::mutex mutex;  // guards worker (the handle) and result; never taken by a sampler
  std::thread worker;
  RequestResult result;
};

void ReorientationController::Impl::finish(PlanOutcome how, std::string message,
                                           plan::PlanRecord record, double best, bool publish_it) {
  std::uint64_t id = 0;
  if (publish_it) {
    try {
      id = runner.publish(record.plan);
    } catch (const InputError& e) {
      how = PlanOutcome::kError;
      message = std::string("the plan's schedule cannot be built: ") + e.what();
      publish_it = false;
    }
  }
  {
    const std::lock_guard<std::mutex> lock(mutex);
    result.outcome = how;
    result.message = std::move(message);
    result.record = std::move(record);
    result.best_distance = best;
    result.plan_id = id;
  }
  outcome.store(how);
  status.store(publish_it ? ControllerStatus::kReady : ControllerStatus::kFailed);
}

planner::PipelineSettings ReorientationController::Impl::pipelineSettings(
    const ReorientationRequest& request) const {
  planner::PipelineSettings pipeline;
  pipeline.method = request.method;
  pipeline.max_attempts = request.max_attempts;
  pipeline.planner = request.planner;
  pipeline.support = request.support;
  pipeline.certificate = request.certificate;
  pipeline.certificate.feedback = feedback;
  pipeline.optimize = request.optimize;
  pipeline.optimizer = request.optimizer;
  return pipeline;
}

void ReorientationController::Impl::run(ReorientationRequest request) {
  double best = 0.0;
  try {
    planner::ReorientationPipeline pipe(model, pipelineSettings(request));
    planner::RunContext context;
    context.cancel = &cancel;
    if (request.progress)
      context.on_event = [&request](const planner::PipelineEvent& e) {
        if (const auto* p = std::get_if<planner::SearchProgress>(&e)) request.progress(p->progress);
      };
    planner::PipelineOutcome out = pipe.run(request.problem, context);
    best = out.best_distance;
    const planner::PipelineAttempt* chosen = out.chosenAttempt();
    std::string note;
    if (chosen != nullptr && !chosen->refined && !chosen->note.empty()) note = chosen->note + "; ";
    plan::PlanRecord& record = out.record;
    switch (out.status) {
      case planner::PipelineStatus::kCancelled:
        finish(PlanOutcome::kCancelled, "cancelled after " + std::to_string(out.wall_time) + " s",
               std::move(record), best, false);
        return;
      case planner::PipelineStatus::kNoPlan:
        finish(PlanOutcome::kNoPath, "the planner produced no path", {}, best, false);
        return;
      case planner::PipelineStatus::kApproximate:
        note += plan::verdictText(record.certificate);
        finish(PlanOutcome::kApproximate,
               "time limit: closest approach " + std::to_string(best) + " tolerance units; " + note,
               std::move(record), best, request.accept_approximate);
        return;
      case planner::PipelineStatus::kNotCertified:
        note += plan::verdictText(record.certificate);
        finish(PlanOutcome::kNotCertified, std::move(note), std::move(record), best,
               request.accept_uncertified);
        return;
      case planner::PipelineStatus::kCertified:
        note += plan::verdictText(record.certificate);
        finish(chosen->refined ? PlanOutcome::kOptimized : PlanOutcome::kExact, std::move(note),
               std::move(record), best, true);
        return;
    }
  } catch (const InputError& e) {
    finish(PlanOutcome::kInputError, e.what(), {}, best, false);
  } catch (const std::exception& e) {
    finish(PlanOutcome::kError, e.what(), {}, best, false);
  }
}

bool ReorientationController::load(const plan::PlanRecord& record, std::string* why,
                                   bool accept_uncertified) {
  executor::LoadOptions options;
  options.accept_uncertified = accept_uncertified;
  return load(record, why, options);
}

bool ReorientationController::load(const plan::PlanRecord& record, std::string* why,
                                   const executor::LoadOptions& options) {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  if (impl_->status.load() == ControllerStatus::kPlanning) {
    if (why != nullptr) *why = "a request is planning: cancel() it and wait() first";
    return false;
  }
  if (impl_->worker.joinable()) impl_->worker.join();  // finished: returns at once
  std::uint64_t id = 0;
  if (!impl_->runner.load(record, why, options, &id)) return false;
  const plan::Certificate& certificate = record.certificate;
  impl_->result.outcome = PlanOutcome::kLoaded;
  impl_->result.message = certificate.ran
                              ? "loaded; its certificate: " + plan::verdictText(certificate)
                              : "loaded; the plan carries no certificate";
  impl_->result.record = record;
  impl_->result.best_distance = 0.0;
  impl_->result.plan_id = id;
  impl_->outcome.store(PlanOutcome::kLoaded);
  impl_->status.store(ControllerStatus::kReady);
  return true;
}

bool ReorientationController::loadFile(const std::string& path, std::string* why,
                                       bool accept_uncertified) {
  executor::LoadOptions options;
  options.accept_uncertified = accept_uncertified;
  return loadFile(path, why, options);
}

bool ReorientationController::loadFile(const std::string& path, std::string* why,
                                       const executor::LoadOptions& options) {
  plan::PlanRecord record;
  return executor::readPlanFile(path, record, why) && load(record, why, options);
}

ReorientationController::ReorientationController(const std::string& cell_file,
                                                 const FeedbackSettings& feedback,
                                                 const ExecutionLimits& limits)
    : ReorientationController(loadCell(cell_file), feedback, limits) {}

ReorientationController::ReorientationController(Cell cell, const FeedbackSettings& feedback,
                                                 const ExecutionLimits& limits)
    : impl_(std::make_unique<Impl>(std::move(cell), feedback, limits)) {}

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

bool ReorientationController::resume(ReorientationRequest request) {
  Pose part;
  double theta = 0.0;
  if (!impl_->runner.heldState(part, theta)) return false;
  request.problem.start = part;
  request.problem.start_theta = theta;
  return plan(request);
}

bool ReorientationController::sample(double t, ReferenceSample& out,
                                     std::uint64_t* plan_id) const noexcept {
  return impl_->runner.sample(t, out, plan_id);
}

bool ReorientationController::track(double t, const VecU& joints, VecU& tau,
                                    std::uint64_t* plan_id) noexcept {
  return impl_->runner.step(t, joints, tau, nullptr, plan_id);
}

bool ReorientationController::track(double t, const VecU& joints, VecU& tau,
                                    ExecutionStatus& status, std::uint64_t* plan_id) noexcept {
  return impl_->runner.step(t, joints, tau, &status, plan_id);
}

void ReorientationController::addPartPose(double stamp, const Pose& pose) noexcept {
  impl_->runner.addPartPose(stamp, pose);
}

void ReorientationController::start() noexcept { impl_->runner.start(); }

void ReorientationController::hold() noexcept { impl_->runner.hold(); }

bool ReorientationController::heldState(Pose& part, double& theta) const noexcept {
  return impl_->runner.heldState(part, theta);
}

double ReorientationController::timeStep() const noexcept { return impl_->runner.timeStep(); }

bool ReorientationController::publishedPlan(double& duration, VecQ& q0) const noexcept {
  return impl_->runner.publishedPlan(duration, q0);
}

std::uint64_t ReorientationController::planId() const noexcept { return impl_->runner.planId(); }

}  // namespace rbsf::controller
