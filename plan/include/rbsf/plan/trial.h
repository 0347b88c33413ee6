#pragma once
/// \file
/// \brief One closed-loop trial of a plan: a plant drawn from the cell's uncertainty, the
///        cell's sensors (noise, rate, latency) and the control law (control_law.h), judged
///        by outcome. certificate.h runs many.
///
/// Draw (drawTrial), each uniform in +- the cell's uncertainty (sensing.h), in this order
/// from a generator seeded by (seed, index): part mass and inertia (relative), the COM
/// offset d in x and y of the part frame, mu_s (relative), mu_k (in [min, max] when the
/// cell's is 0, else scaled as mu_s; never above mu_s), the start pose (x, y, phi) of the
/// part's frame, each input's actuator gain, and the seed of the sensors' noise. The
/// plant's shape is the cell's shifted by -d (Shape::shifted); its start is the drawn pose
/// with the fingers placed under the part (placement.h) at the plan's start_theta.
///
/// Run (runTrial): steps of the plan's simulator over the plan and the schedule's settle
/// hold. Faults (the cell's `faults` section, faults.h), when drawn: a mass error scales the
/// plant's part mass; a dropout withholds the part poses taken in it; a spike makes one
/// joint reading NaN or off by its size; a missed tick holds the last input one more period
/// without running the law; a force cut clamps one finger's input to its cut limit. A trial
/// with faults runs the executor's holds (ExecutionLimits hold_on_leaving, hold_on_faults:
/// the cell's own safety) and records how it ended: done, held, lost or off (TrialEnd).
/// Each period the law gets the joints measured (true + Gaussian noise) and, at the
/// sensor's rate, the pose of the part's frame (true + noise) stamped when taken and
/// handed over `latency` later. The input applied is the law's times the actuator gains;
/// open loop it is the plan's feed-forward alone. The part's frame is the COM frame moved
/// back by -d: what a sensor sees and what the goal describes. The law runs inside a
/// PlanExecutor (plan_executor.h), whose status the outcome keeps (TrialOutcome: largest
/// deviations, first leaving, hold); where the law runs on the joints alone and the cell has
/// a part-pose sensor, that sensor (its own noise) still serves the status. The executor
/// holds the part only where settings.execution says so.
///
/// Success: never dropped (no contact touching for drop_time, the part's frame farther
/// than lost_distance from the reference, or a non-finite state: the trial stops there);
/// the final pose within position_tolerance and angle_tolerance of the goal (angle as in
/// the plan's own turn: the goal angle taken within pi of the plan's final angle); at rest
/// by the cell's one rest rule, the one its plans end in (motion_limits.h `rest`): the mean
/// speed and angular speed over the last rest_window at most rest_speed and
/// rest_angular_speed of the schedule's cell (the mean, so that sensor-driven jitter around
/// a pose counts as rest and a drift does not); and the law demanding more than an input's limit
/// (which the actuator clamps) for at most saturation_time in all.

#include <cstdint>
#include <vector>

#include "rbsf/dynamics/control/execution_status.h"
#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/trajectory_sample.h"
#include "rbsf/plan/certificate_report.h"
#include "rbsf/plan/plan.h"
#include "rbsf/plan/trial_faults.h"

namespace rbsf::plan {

/// \brief Criteria and limits of a trial (file comment).
struct TrialSettings {
  double position_tolerance = 0.01;           ///< [m]
  double angle_tolerance = 2.0 * M_PI / 180;  ///< [rad]
  /// \brief The rest is the mean speed over the trial's last rest_window [s] against the
  ///        cell's motion_limits rest: by default the last second, the schedule's hold after
  ///        the plan's end (a held part under the camera's noise moved 0.05 deg in 0.5 s,
  ///        twice the default rest over that window, and stays within it over 1 s).
  double rest_window = 1.0;
  /// \brief The law may demand more than an input's limit (the actuator clamps) for at
  ///        most this long in total [s].
  double saturation_time = 0.02;
  double drop_time = 0.05;      ///< [s] with no contact touching
  double lost_distance = 0.3;   ///< [m] from the reference
  double min_phase_run = 0.02;  ///< phase runs shorter than this not reported [s]
  /// \brief The execution status's limits (execution_status.h). A certificate judges the
  ///        law itself, so its trials hold on nothing: the status is watched, not obeyed.
  ExecutionLimits execution = [] {
    ExecutionLimits e;
    e.hold_on_leaving = false;
    e.hold_on_faults = false;
    return e;
  }();
};

/// \brief One trial's plant, start, actuators and noise (file comment).
struct TrialDraw {
  Cell cell;                     ///< the plant
  Vec2 com_offset;               ///< d: the plant's COM in the plan's part frame [m]
  VecQ q0;                       ///< the plant's start (its COM pose), at rest
  VecU actuator_gain;            ///< input j is applied times actuator_gain[j]
  std::uint64_t noise_seed = 0;  ///< of the sensors' noise
  bool noise = true;             ///< false: the sensors measure exactly
  FaultDraw faults;              ///< drawn from the cell's faults section (none by default)
};

/// \brief Draw trial `index` of `seed` for `plan` on `cell` (file comment). The faults
///        come from a generator of their own, so a cell without them draws as before.
/// \throws InputError when the plan's start cannot be placed on the cell at all.
TrialDraw drawTrial(const Cell& cell, const Plan& plan, std::uint64_t seed, int index);

/// \brief The draw of a trial without uncertainty or sensor noise: the cell itself, the
///        plan's start, unit gains (what the plan was made for).
TrialDraw nominalDraw(const Cell& cell, const Plan& plan);

/// \brief Run one trial (file comment) with the law of `schedule` (made for this plan), or
///        open loop. `trace`, when given, receives every step's true state.
TrialOutcome runTrial(const FeedbackSchedule& schedule, const Plan& plan, const TrialDraw& draw,
                      const TrialSettings& settings, bool open_loop,
                      std::vector<TrajectorySample>* trace = nullptr);

}  // namespace rbsf::plan
