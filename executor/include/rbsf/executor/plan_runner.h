#pragma once
/// \file
/// \brief What a cell links to execute plan files: a plan checked against the cell and
///        published to a real-time loop, which runs it with the control law behind an input
///        guard, a status every tick and a safe hold (rbsf/dynamics/control/plan_executor.h).
///        Needs rbsf::dynamics and rbsf::plan only (no OMPL, no Ipopt); the planning facade
///        (rbsf/controller/reorientation_controller.h) publishes its plans through one.
///
/// Threads. load(), loadFile() and publish() may be called from any non-real-time thread
/// (they build the plan's feedback schedule: tens of milliseconds for a 5 s plan; they are
/// serialised among themselves). sample(), publishedPlan(), planId(), timeStep() and
/// heldState() may be called from any thread at any time: they take no lock and allocate
/// nothing. start(), step(), addPartPose() and hold() belong to one real-time loop thread
/// (they too take no lock and allocate nothing).
///
/// A run. The loop calls start() when it is about to run the published plan, then step()
/// every control period h = timeStep() with the plan time t (0 at the start) and the joints
/// measured at t, and hands over part poses as they arrive. The first step() after a new
/// plan is published also starts a run of it. After the plan's end the law holds the final
/// pose at rest; a hold (the status's verdict, or hold()) brings the reference to rest on
/// the plan's path and keeps it there until the next start().

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "rbsf/dynamics/control/execution_status.h"
#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/control/reference_trajectory.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/plan/plan_file.h"

namespace rbsf::executor {

/// \brief What load() accepts beyond a plan certified for this very cell.
struct LoadOptions {
  /// \brief A plan without a certificate, or with a failed one.
  bool accept_uncertified = false;
  /// \brief A plan whose friction or certificate's draws (uncertainty, sensing) differ from
  ///        this cell's (plan_fit.h certificateCellMismatch): its evidence speaks for another
  ///        cell.
  bool accept_other_evidence = false;
};

/// \brief Read the plan file `path` (plan_file.h readPlanJson) into `record`; false, with the
///        reader's message in `why`, when it cannot be read or parsed.
bool readPlanFile(const std::string& path, plan::PlanRecord& record, std::string* why);

/// \brief Plans published to one real-time loop, and their execution (file comment).
class PlanRunner {
 public:
  /// \brief For the cell `cell` (the law's gains from `feedback`, the status's bands from
  ///        `limits`). \throws InputError when the cell is invalid.
  explicit PlanRunner(Cell cell, const FeedbackSettings& feedback = {},
                      const ExecutionLimits& limits = {});
  /// \brief For the cell file `cell_file`. \throws InputError naming the key or file.
  explicit PlanRunner(const std::string& cell_file, const FeedbackSettings& feedback = {},
                      const ExecutionLimits& limits = {});
  ~PlanRunner();
  PlanRunner(const PlanRunner&) = delete;
  PlanRunner& operator=(const PlanRunner&) = delete;

  const RbsfModel& model() const;
  const FeedbackSettings& feedback() const;
  const ExecutionLimits& limits() const;

  /// \brief Publish `record`'s plan after checking it: made for this cell (plan_fit.h
  ///        planCellMismatch), its evidence drawn for this cell (certificateCellMismatch,
  ///        unless accept_other_evidence) and certified (unless accept_uncertified).
  ///        Refused, with `why` set and nothing published, otherwise. Returns the new plan's
  ///        id in `id` when given.
  bool load(const plan::PlanRecord& record, std::string* why = nullptr,
            const LoadOptions& options = {}, std::uint64_t* id = nullptr);
  /// \brief load() of a plan file (plan_file.h readPlanJson); a file that cannot be read is
  ///        refused with the reader's message.
  bool loadFile(const std::string& path, std::string* why = nullptr,
                const LoadOptions& options = {}, std::uint64_t* id = nullptr);
  /// \brief Publish `plan` as it is (the planning facade, after its own certificate).
  ///        \return its id. \throws InputError when its schedule cannot be built.
  std::uint64_t publish(const plan::Plan& plan);

  /// \brief Sample the published plan at t [s] (clamped to the plan): false when none.
  bool sample(double t, ReferenceSample& out, std::uint64_t* plan_id = nullptr) const noexcept;
  /// \brief Duration [s] and start configuration q0 of the published plan; false when none.
  bool publishedPlan(double& duration, VecQ& q0) const noexcept;
  /// \brief Id of the published plan (0: none; ids start at 1).
  std::uint64_t planId() const noexcept;
  /// \brief The published plan's control period h [s] (its simulator's step), 0 when none:
  ///        step() expects to be called every h.
  double timeStep() const noexcept;

  /// \brief The next step() starts a fresh run of the published plan at its t (0 for the
  ///        plan's start). Loop thread.
  void start() noexcept;
  /// \brief The input for [t, t + h) from the joints measured at t (theta, l_1..l_m), and
  ///        the tick's status (execution_status.h) in `status` when given. False (tau and
  ///        status untouched) when no plan is published or the joints have the wrong size.
  ///        Non-finite readings are the executor's to bridge (plan_executor.h). Loop thread.
  bool step(double t, const VecU& joints, VecU& tau, ExecutionStatus* status = nullptr,
            std::uint64_t* plan_id = nullptr) noexcept;
  /// \brief A part pose taken at plan time `stamp`, for the law and the status. Loop thread.
  void addPartPose(double stamp, const Pose& pose) noexcept;
  /// \brief Hold the part (the reason kCommanded); no effect before a run. Loop thread.
  void hold() noexcept;
  /// \brief Where the held part is estimated (its pose and the base angle), as the loop
  ///        thread last stepped while holding: the start to plan again from. False when the
  ///        run is not holding. Any thread.
  bool heldState(Pose& part, double& theta) const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rbsf::executor
