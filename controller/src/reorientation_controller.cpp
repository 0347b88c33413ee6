#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/io/cell_file.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <variant>

#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/plan/plan_fit.h"
#include "rbsf/plan/plan_reference.h"
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

namespace {

/// \brief What a real-time reader sees: one plan's schedule (reference and gains), and
///        the law the loop thread runs on it (its only mutable part).
struct PublishedPlan {
  PublishedPlan(std::uint64_t id_, const RbsfModel& model, const plan::Plan& plan,
                const FeedbackSettings& feedback)
      : id(id_),
        duration(plan.duration()),
        q0(plan.q0),
        schedule(model, plan::makeReference(plan), plan::lawSensing(model.cell().sensing, plan),
                 plan.simulator, feedback),
        law(schedule) {}

  std::uint64_t id;
  double duration;
  VecQ q0;
  FeedbackSchedule schedule;
  mutable ControlLaw law;  ///< the loop thread's alone (track, addPartPose)
};

}  // namespace

struct ReorientationController::Impl {
  Impl(Cell cell, const FeedbackSettings& feedback_settings)
      : model(std::move(cell)), feedback(feedback_settings) {}

  void run(ReorientationRequest request);
  /// \brief The loop thread meets plan `p`: a plan it has not met starts its law afresh.
  void start(const PublishedPlan& p) noexcept {
    if (p.id == tracked_id) return;
    p.law.reset();
    tracked_id = p.id;
  }
  void finish(PlanOutcome outcome, std::string message, plan::PlanRecord record, double best,
              bool publish_it);
  /// \brief The pipeline's settings of `request` on this cell, with the facade's feedback.
  planner::PipelineSettings pipelineSettings(const ReorientationRequest& request) const;

  const RbsfModel model;
  const FeedbackSettings feedback;
  detail::SnapshotSlots<PublishedPlan> slots;
  std::atomic<ControllerStatus> status{ControllerStatus::kIdle};
  std::atomic<PlanOutcome> outcome{PlanOutcome::kNone};
  std::atomic<bool> cancel{false};
  std::uint64_t next_id = 1;     // worker only (one at a time)
  std::uint64_t tracked_id = 0;  // loop thread only: the plan whose law track() last ran

  std::mutex mutex;  // guards worker (the handle) and result; never taken by a sampler
  std::thread worker;
  RequestResult result;
};

void ReorientationController::Impl::finish(PlanOutcome how, std::string message,
                                           plan::PlanRecord record, double best, bool publish_it) {
  std::uint64_t id = 0;
  if (publish_it) {
    id = next_id++;
    slots.publish(std::make_unique<const PublishedPlan>(id, model, record.plan, feedback));
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
  auto refuse = [&](std::string text) {
    if (why != nullptr) *why = std::move(text);
    return false;
  };
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  if (impl_->status.load() == ControllerStatus::kPlanning)
    return refuse("a request is planning: cancel() it and wait() first");
  if (impl_->worker.joinable()) impl_->worker.join();  // finished: returns at once
  const plan::Plan& plan = record.plan;
  const plan::Certificate& certificate = record.certificate;
  const std::string mismatch = plan::planCellMismatch(impl_->model, plan);
  if (!mismatch.empty()) return refuse(mismatch);
  if (!accept_uncertified && !certificate.certified)
    return refuse(certificate.ran
                      ? "the plan is not certified (" + plan::verdictText(certificate) + ")"
                      : "the plan carries no certificate");
  std::unique_ptr<const PublishedPlan> published;
  try {
    published =
        std::make_unique<const PublishedPlan>(impl_->next_id, impl_->model, plan, impl_->feedback);
  } catch (const InputError& e) {
    return refuse(e.what());
  }
  const std::uint64_t id = impl_->next_id++;
  impl_->slots.publish(std::move(published));
  impl_->result.outcome = PlanOutcome::kLoaded;
  impl_->result.message = certificate.ran
                              ? "loaded; its certificate: " + plan::verdictText(certificate)
                              : "loaded; the plan carries no certificate";
  impl_->result.record = record;
  impl_->result.best_distance = 0.0;
  impl_->result.plan_id = id;
  impl_->outcome.store(PlanOutcome::kLoaded);
  impl_->status.store(ControllerStatus::kReady);
  if (why != nullptr) why->clear();
  return true;
}

bool ReorientationController::loadFile(const std::string& path, std::string* why,
                                       bool accept_uncertified) {
  plan::PlanRecord record;
  try {
    record = plan::readPlanJson(path);
  } catch (const InputError& e) {
    if (why != nullptr) *why = e.what();
    return false;
  }
  return load(record, why, accept_uncertified);
}

ReorientationController::ReorientationController(const std::string& cell_file,
                                                 const FeedbackSettings& feedback)
    : ReorientationController(loadCell(cell_file), feedback) {}

ReorientationController::ReorientationController(Cell cell, const FeedbackSettings& feedback)
    : impl_(std::make_unique<Impl>(std::move(cell), feedback)) {}

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
  p->schedule.reference(std::min(t, p->duration), out);
  if (plan_id != nullptr) *plan_id = p->id;
  return true;
}

bool ReorientationController::track(double t, const VecU& joints, VecU& tau,
                                    std::uint64_t* plan_id) noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return false;
  if (joints.size() != impl_->model.controlDim()) return false;
  impl_->start(*p);
  p->law.compute(t, joints, tau);
  if (plan_id != nullptr) *plan_id = p->id;
  return true;
}

void ReorientationController::addPartPose(double stamp, const Pose& pose) noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return;
  impl_->start(*p);
  p->law.addPartPose(stamp, pose);
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
