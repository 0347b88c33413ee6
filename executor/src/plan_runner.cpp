#include "rbsf/executor/plan_runner.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "rbsf/dynamics/control/plan_executor.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate_report.h"
#include "rbsf/plan/plan_fit.h"
#include "rbsf/plan/plan_reference.h"
#include "snapshot_slots.h"

namespace rbsf::executor {

namespace {

/// \brief What a real-time reader sees: one plan's schedule (reference and gains), and the
///        executor the loop thread runs on it (its only mutable part).
struct PublishedPlan {
  PublishedPlan(std::uint64_t id_, const RbsfModel& model, const plan::Plan& plan,
                const FeedbackSettings& feedback, const ExecutionLimits& limits)
      : id(id_),
        duration(plan.duration()),
        q0(plan.q0),
        schedule(model, plan::makeReference(plan), plan::lawSensing(model.cell().sensing, plan),
                 plan.simulator, feedback),
        executor(schedule, limits) {}

  std::uint64_t id;
  double duration;
  VecQ q0;
  FeedbackSchedule schedule;
  mutable PlanExecutor executor;  ///< the loop thread's alone
};

}  // namespace

struct PlanRunner::Impl {
  Impl(Cell cell, const FeedbackSettings& f, const ExecutionLimits& l)
      : model(std::move(cell)), feedback(f), limits(l) {}

  /// \brief The loop thread meets plan `p`: a plan it has not met, or a start() asked,
  ///        begins a fresh run.
  void meet(const PublishedPlan& p) noexcept {
    if (p.id == run_id && !restart) return;
    p.executor.reset();
    run_id = p.id;
    restart = false;
  }
  /// \brief The loop thread's record of the held state, for heldState() on any thread.
  void recordHeld(const PlanExecutor& e) noexcept {
    const bool holding = e.law().holding();
    if (!holding && !held_valid.load(std::memory_order_relaxed)) return;
    held_seq.fetch_add(1, std::memory_order_acq_rel);  // odd: writing
    if (holding) {
      const VecQ& q = e.law().controlState();
      held[0].store(q[layout::kX], std::memory_order_relaxed);
      held[1].store(q[layout::kY], std::memory_order_relaxed);
      held[2].store(q[layout::kPhi], std::memory_order_relaxed);
      held[3].store(q[layout::kTheta], std::memory_order_relaxed);
    }
    held_valid.store(holding, std::memory_order_relaxed);
    held_seq.fetch_add(1, std::memory_order_release);  // even: done
  }

  const RbsfModel model;
  const FeedbackSettings feedback;
  const ExecutionLimits limits;
  detail::SnapshotSlots<PublishedPlan> slots;
  std::mutex publishing;      // serialises load() and publish()
  std::uint64_t next_id = 1;  // under `publishing`
  std::uint64_t run_id = 0;   // loop thread: the plan whose run step() last advanced
  bool restart = false;       // loop thread: start() asked
  std::atomic<std::uint64_t> held_seq{0};
  std::atomic<bool> held_valid{false};
  std::array<std::atomic<double>, 4> held{};
};

PlanRunner::PlanRunner(Cell cell, const FeedbackSettings& feedback, const ExecutionLimits& limits)
    : impl_(std::make_unique<Impl>(std::move(cell), feedback, limits)) {}

PlanRunner::PlanRunner(const std::string& cell_file, const FeedbackSettings& feedback,
                       const ExecutionLimits& limits)
    : PlanRunner(loadCell(cell_file), feedback, limits) {}

PlanRunner::~PlanRunner() = default;

const RbsfModel& PlanRunner::model() const { return impl_->model; }
const FeedbackSettings& PlanRunner::feedback() const { return impl_->feedback; }
const ExecutionLimits& PlanRunner::limits() const { return impl_->limits; }

bool PlanRunner::load(const plan::PlanRecord& record, std::string* why, const LoadOptions& options,
                      std::uint64_t* id) {
  auto refuse = [&](std::string text) {
    if (why != nullptr) *why = std::move(text);
    return false;
  };
  const std::string mismatch = plan::planCellMismatch(impl_->model, record.plan);
  if (!mismatch.empty()) return refuse(mismatch);
  if (!options.accept_other_evidence) {
    const std::string other = plan::certificateCellMismatch(impl_->model, record);
    if (!other.empty()) return refuse(other + " (accept_other_evidence loads it anyway)");
  }
  const plan::Certificate& certificate = record.certificate;
  if (!options.accept_uncertified && !certificate.certified)
    return refuse(certificate.ran
                      ? "the plan is not certified (" + plan::verdictText(certificate) + ")"
                      : "the plan carries no certificate");
  try {
    const std::uint64_t published = publish(record.plan);
    if (id != nullptr) *id = published;
  } catch (const InputError& e) {
    return refuse(e.what());
  }
  if (why != nullptr) why->clear();
  return true;
}

bool readPlanFile(const std::string& path, plan::PlanRecord& record, std::string* why) {
  try {
    record = plan::readPlanJson(path);
  } catch (const InputError& e) {
    if (why != nullptr) *why = e.what();
    return false;
  }
  return true;
}

bool PlanRunner::loadFile(const std::string& path, std::string* why, const LoadOptions& options,
                          std::uint64_t* id) {
  plan::PlanRecord record;
  return readPlanFile(path, record, why) && load(record, why, options, id);
}

std::uint64_t PlanRunner::publish(const plan::Plan& plan) {
  const std::lock_guard<std::mutex> lock(impl_->publishing);
  auto p = std::make_unique<const PublishedPlan>(impl_->next_id, impl_->model, plan,
                                                 impl_->feedback, impl_->limits);
  const std::uint64_t id = impl_->next_id++;
  impl_->slots.publish(std::move(p));
  return id;
}

bool PlanRunner::sample(double t, ReferenceSample& out, std::uint64_t* plan_id) const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return false;
  p->schedule.reference(std::min(t, p->duration), out);
  if (plan_id != nullptr) *plan_id = p->id;
  return true;
}

bool PlanRunner::publishedPlan(double& duration, VecQ& q0) const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return false;
  duration = p->duration;
  q0 = p->q0;
  return true;
}

std::uint64_t PlanRunner::planId() const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  return reader.get() == nullptr ? 0 : reader.get()->id;
}

double PlanRunner::timeStep() const noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  return reader.get() == nullptr ? 0.0 : reader.get()->schedule.timeStep();
}

void PlanRunner::start() noexcept { impl_->restart = true; }

bool PlanRunner::step(double t, const VecU& joints, VecU& tau, ExecutionStatus* status,
                      std::uint64_t* plan_id) noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr || joints.size() != impl_->model.controlDim()) return false;
  impl_->meet(*p);
  p->executor.step(t, joints, tau);
  impl_->recordHeld(p->executor);
  if (status != nullptr) *status = p->executor.status();
  if (plan_id != nullptr) *plan_id = p->id;
  return true;
}

void PlanRunner::addPartPose(double stamp, const Pose& pose) noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr) return;
  impl_->meet(*p);
  p->executor.addPartPose(stamp, pose);
}

void PlanRunner::hold() noexcept {
  const detail::SnapshotSlots<PublishedPlan>::Reader reader(impl_->slots);
  const PublishedPlan* p = reader.get();
  if (p == nullptr || p->id != impl_->run_id) return;
  p->executor.hold(HoldReason::kCommanded);
  impl_->recordHeld(p->executor);
}

bool PlanRunner::heldState(Pose& part, double& theta) const noexcept {
  for (;;) {
    const std::uint64_t before = impl_->held_seq.load(std::memory_order_acquire);
    if (before % 2 != 0) continue;  // the loop thread is writing
    const bool valid = impl_->held_valid.load(std::memory_order_relaxed);
    const double x = impl_->held[0].load(std::memory_order_relaxed);
    const double y = impl_->held[1].load(std::memory_order_relaxed);
    const double phi = impl_->held[2].load(std::memory_order_relaxed);
    const double th = impl_->held[3].load(std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (impl_->held_seq.load(std::memory_order_relaxed) != before) continue;
    if (!valid) return false;
    part = Pose{x, y, phi};
    theta = th;
    return true;
  }
}

}  // namespace rbsf::executor
