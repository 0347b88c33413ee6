#pragma once
/// \file
/// \brief The library's face for a cell controller: load a cell, plan and certify a
///        reorientation on a worker thread, and execute the plan from a real-time loop with
///        the control law (rbsf/dynamics/control/control_law.h).
///
/// Threads. plan() starts a worker thread and returns at once; the worker runs the
/// pipeline (planner/pipeline/reorientation_pipeline.h: the planners and, when asked, the
/// optimiser), which certifies the result (plan/certificate.h: closed-loop trials under the cell's
/// sensing and uncertainty), builds the plan's feedback schedule and publishes it. Any number of
/// threads may call sample(), publishedPlan(), status(), outcome() and planId() at any time, also
/// while the worker runs: they take no lock, allocate nothing and free nothing (the published plan
/// is an immutable snapshot handed over through three slots; see src/snapshot_slots.h). track() and
/// addPartPose() run the control law's estimator, which has state: call them from one real-time
/// loop thread only (they too take no lock and allocate nothing). The other members (plan(),
/// cancel(), wait(), result()) may be called from any non-real-time thread; cancel() is also
/// async-signal-safe.
///
/// Plan time. A plan starts at t = 0 with the part at rest at the problem's start (q0 =
/// the fingers placed at start_theta) and ends at its duration (publishedPlan()); after it
/// the law holds the final pose at rest. Sampling clamps t to the plan.
///
/// A plan made elsewhere (a plan file of plan-reorientation) is published by load() or
/// loadFile(): status() kReady, outcome() kLoaded, once it is checked against this cell.
///
/// Life of a request: status() goes kIdle -> kPlanning -> kReady (a plan was published:
/// outcome() kExact or kOptimized, a certified plan; kApproximate or kNotCertified only
/// when the request accepts them) or kFailed (outcome() says why: kNotCertified,
/// kCancelled, kApproximate, kNoPath, kInputError, kError; result().message the details).
/// A failed or cancelled request leaves the previously published plan (if any) in place:
/// sample() keeps returning it, and planId() tells which plan it is.
///
/// Execution. Plans are published through an executor::PlanRunner (the component a cell
/// that only executes plan files links alone: rbsf/executor/plan_runner.h); track() is its
/// step(): the control law behind an input guard, with a status every tick and a safe hold
/// (rbsf/dynamics/control/plan_executor.h). A run that holds (its status's verdict kHolding)
/// stays held until start() or a new plan; resume() plans again from where it is held.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "rbsf/dynamics/control/execution_status.h"
#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/control/reference_trajectory.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/executor/plan_runner.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/planner/pipeline/reorientation_pipeline.h"
#include "rbsf/planner/planner_settings.h"
#include "rbsf/trajopt/optimizer_settings.h"

namespace rbsf::controller {

/// \brief Where the controller's current request stands.
enum class ControllerStatus : std::uint8_t {
  kIdle,      ///< no request yet
  kPlanning,  ///< the worker is planning (or optimising)
  kReady,     ///< the request's plan is published
  kFailed     ///< the request ended without publishing; see outcome()
};

/// \brief How the last finished request ended.
enum class PlanOutcome : std::uint8_t {
  kNone,          ///< no request finished yet
  kExact,         ///< planner reached the goal; its certified plan is published
  kOptimized,     ///< and the optimiser refined it; the certified refined plan is published
  kLoaded,        ///< a plan given to load() / loadFile() is published as given
  kNotCertified,  ///< the plan failed its certificate (published only when accepted)
  kApproximate,   ///< the search ended away from the goal (published only when accepted)
  kNoPath,        ///< the planner produced no path
  kCancelled,     ///< cancel() stopped the request
  kInputError,    ///< the problem or settings were refused (message names what)
  kError          ///< anything else (message)
};

/// \brief "idle", "planning", "ready", "failed"; "none", "exact", "optimized", ...
const char* toString(ControllerStatus status);
const char* toString(PlanOutcome outcome);

/// \brief One reorientation request.
struct ReorientationRequest {
  planner::Problem problem;  ///< start pose (part at rest), start_theta, goal pose
  /// \brief The planner's settings (cancel() and `progress` are the request's run
  ///        context, not settings). The default differs from PlannerSettings' in one place:
  ///        sample_steps = 1, a plan sample (a reference knot) every simulator step, so that the
  ///        reference passes through every simulated state; with 10 ms knots the cubic between them
  ///        strays ~0.3 mm from the simulated path, which a feedback law then answers.
  planner::PlannerSettings planner = [] {
    planner::PlannerSettings s;
    s.sample_steps = 1;
    return s;
  }();
  /// \brief Refine the exact plan with rbsf::trajopt; of the planner's plan and the refined
  ///        one the plan with the better certificate is published (refine_and_certify.h).
  bool optimize = false;
  trajopt::OptimizerSettings optimizer;  ///< the refinement's settings
  /// \brief How the plan is certified (a fixed count of trials or the sequential default,
  ///        the confidence bound, seed, criteria: plan/certificate.h); the trials run on
  ///        the worker thread, on every core.
  plan::CertificateSettings certificate;
  /// \brief Which planners (reorientation_pipeline.h). The default, the kinodynamic planner
  ///        alone, suits a cell that senses the part; kAuto tries the support planner (plans
  ///        the joints alone hold) first.
  planner::PipelineMethod method = planner::PipelineMethod::kKinodynamic;
  /// \brief The support planner, for kAuto (its time_limit, cancel and feedback are set
  ///        from the request and the facade). Its max_expansions bounds its searches by
  ///        work, so that a plan does not depend on the machine's speed.
  planner::SupportPlannerSettings support;
  /// \brief Kinodynamic searches at most, seed after seed, until one certifies (0: while
  ///        planner.time_limit lasts).
  int max_attempts = 1;
  bool accept_approximate = false;  ///< publish a plan that ends away from the goal
  /// \brief Publish a plan that failed its certificate (outcome kNotCertified). Off: such
  ///        a plan is kept in result() only; a cell should not run it.
  bool accept_uncertified = false;
  /// \brief Called on the worker thread about once per second while searching.
  std::function<void(const planner::Progress&)> progress;
};

/// \brief What the last finished request produced (copied; not for the real-time loop).
struct RequestResult {
  PlanOutcome outcome = PlanOutcome::kNone;
  std::string message;         ///< why it failed, or the certificate's verdict
  plan::PlanRecord record;     ///< the plan (published or not), its certificate and summary
  double best_distance = 0.0;  ///< planner's best goal distance [tolerance units]
  std::uint64_t plan_id = 0;   ///< id of the published plan, 0 when not published
};

/// \brief Controller facade for one cell (see the file comment for the threading rules).
class ReorientationController {
 public:
  /// \brief Load the cell file (its sensing section says which law runs); `limits` are the
  ///        execution status's bands and holds (execution_status.h).
  /// \throws InputError naming the key or file.
  explicit ReorientationController(const std::string& cell_file,
                                   const FeedbackSettings& feedback = {},
                                   const ExecutionLimits& limits = {});
  /// \brief Use a cell built in code. \throws InputError when it is invalid.
  explicit ReorientationController(Cell cell, const FeedbackSettings& feedback = {},
                                   const ExecutionLimits& limits = {});
  /// \brief Cancels a running request and joins the worker.
  ~ReorientationController();
  ReorientationController(const ReorientationController&) = delete;
  ReorientationController& operator=(const ReorientationController&) = delete;

  const RbsfModel& model() const;

  /// \brief Start planning `request` on a worker thread and return at once. Returns false
  ///        (and starts nothing) while a request is still planning: cancel() it and wait().
  bool plan(const ReorientationRequest& request);
  /// \brief Publish a plan made elsewhere (by plan-reorientation, or an earlier request)
  ///        for track() and sample(), with its own law (plan::lawSensing) and a fresh
  ///        schedule; status() kReady, outcome() kLoaded, result() the plan and a message
  ///        with the certificate it carries (the controller does not certify it again).
  ///        Refused, with `why` set and nothing published, while a request is planning,
  ///        when the plan was made for another cell (plan/plan_fit.h: fingers, recorded
  ///        masses and offsets, the part's placement at the start), unless told otherwise
  ///        (`options`) when its friction or its certificate's draws are another cell's
  ///        (certificateCellMismatch), and when it carries no certificate or a failed one.
  ///        Not real-time: it builds the schedule (tens of milliseconds for a 5 s plan).
  bool load(const plan::PlanRecord& record, std::string* why, const executor::LoadOptions& options);
  /// \brief load() with options{accept_uncertified}.
  bool load(const plan::PlanRecord& record, std::string* why = nullptr,
            bool accept_uncertified = false);
  /// \brief load() of a plan file (plan_file.h readPlanJson); a file that cannot be read or
  ///        parsed is refused with the reader's message.
  bool loadFile(const std::string& path, std::string* why, const executor::LoadOptions& options);
  /// \brief loadFile() with options{accept_uncertified}.
  bool loadFile(const std::string& path, std::string* why = nullptr,
                bool accept_uncertified = false);
  /// \brief Ask the running request to stop (the planner at its next check, the optimiser
  ///        at its next iteration); it ends with outcome kCancelled. No effect when idle.
  void cancel() noexcept;
  /// \brief Block until no request is planning (joins the worker).
  void wait();

  /// \brief Status of the current request. Lock-free.
  ControllerStatus status() const noexcept;
  /// \brief Outcome of the last finished request. Lock-free.
  PlanOutcome outcome() const noexcept;
  /// \brief Copy of the last finished request's result (takes a lock; not real-time).
  RequestResult result() const;

  /// \brief Sample the published plan at plan time t [s]: q_ref, v_ref (state_layout.h
  ///        order: joint references are the theta and stroke entries), feed-forward tau
  ///        and planned phase (reference_trajectory.h). Returns false and leaves `out`
  ///        untouched when no plan is published ("no plan"). `plan_id`, when given,
  ///        receives the id of the plan sampled (ids start at 1 and grow by one per
  ///        publication), so a loop sees when a new plan replaced the one it executes.
  ///        Lock-free, allocation-free; safe from any thread while planning runs.
  bool sample(double t, ReferenceSample& out, std::uint64_t* plan_id = nullptr) const noexcept;

  /// \brief The input for the control period [t, t + h) (h: the plan's time step, 1 ms by
  ///        default) from the joints measured at t (theta, l_1..l_m: tau order), by the
  ///        control law of the published plan (control_law.h; with the plan's sensing,
  ///        plan::lawSensing: part feedback when the cell senses the part and the plan is
  ///        not held by the joints alone, joint PD otherwise). The first call of track() or
  ///        addPartPose() after a plan is published starts its law (the estimate at the
  ///        plan's start, the joints as measured). Joints of the wrong size: false.
  ///        Returns false and leaves `tau` untouched when no plan is published; `plan_id`
  ///        receives the plan's id. One real-time thread only; lock-free, allocation-free.
  bool track(double t, const VecU& joints, VecU& tau, std::uint64_t* plan_id = nullptr) noexcept;
  /// \brief track(), and the tick's execution status (execution_status.h: deviation,
  ///        contacts, saturation, the part pose's age, the verdict). A verdict kLeaving, or
  ///        a fault that lasts (a non-finite joint reading bridged past its time, a part-
  ///        feedback run without poses), holds the part from the next tick on. Non-finite
  ///        joints never reach the law. Lock-free, allocation-free.
  bool track(double t, const VecU& joints, VecU& tau, ExecutionStatus& status,
             std::uint64_t* plan_id = nullptr) noexcept;
  /// \brief The next track() starts a fresh run of the published plan (the law and status
  ///        reset, a hold released): t = 0 is the plan's start again. The loop thread.
  void start() noexcept;
  /// \brief Hold the part where the run is (the reference brought to rest on the plan's
  ///        path; status kHolding, reason kCommanded). The loop thread.
  void hold() noexcept;
  /// \brief Where the held part is estimated (its pose and the base angle); false when
  ///        the run is not holding. Any thread.
  bool heldState(Pose& part, double& theta) const noexcept;
  /// \brief Plan `request` again from the held state (heldState(): its start pose and
  ///        start_theta replace the request's), as plan() does. False when the run is not
  ///        holding or a request is planning. Not the loop thread.
  bool resume(ReorientationRequest request);
  /// \brief The published plan's control period [s] (0: none): call track() every period.
  double timeStep() const noexcept;

  /// \brief A pose of the part's frame measured at plan time `stamp` (when the sensor took
  ///        it, not when it arrived); the next track() uses it. The loop thread of track().
  void addPartPose(double stamp, const Pose& pose) noexcept;

  /// \brief Duration [s] and start configuration q0 of the published plan; false when none.
  bool publishedPlan(double& duration, VecQ& q0) const noexcept;
  /// \brief Id of the published plan (0: none). Lock-free.
  std::uint64_t planId() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rbsf::controller
