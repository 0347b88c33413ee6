#pragma once
/// \file
/// \brief A plan: tau segments, the trajectory they produce, and its files.
///
/// JSON (writePlanJson / readPlanJson; keys in this order):
/// | key             | meaning |
/// |-----------------|---------|
/// | `status`        | `"exact"` (goal reached) or `"approximate"` (closest found) |
/// | `planner`, `seed` | planner name and RNG seed |
/// | `planning_time` | wall time of the search [s] |
/// | `propagations`  | propagate() calls (each k simulator steps) |
/// | `goal_distance` | final distance in tolerance units (<= 1 when exact) |
/// | `time_step`     | simulator step h [s]; `steps_per_control` k |
/// | `simulator`     | the simulator's other settings (simulator.h): |
/// |                 | `activation_distance`, `contact_tolerance`, `slip_tolerance`, |
/// |                 | `regularization`, `curvature_terms`, `drift_correction`, |
/// |                 | `max_mode_iterations`; defaults when absent |
/// | `start`, `goal` | poses {x, y, phi}; `start_theta` the base angle at the start |
/// | `q0`            | start configuration (state_layout.h order), at rest |
/// | `phase_sequence` | the segments' phases, runs merged (Plan::phaseSequence) |
/// | `segments[]`    | `phase` ("C", "P" or "U": the phase most steps of the segment |
/// |                 | took in simulation), `duration` [s], `steps`, `tau`; `tau_end` |
/// |                 | only for a ramp (optimised plans): tau goes linearly from `tau` |
/// |                 | to `tau_end` over the segment |
/// | `samples[]`     | every `sample_steps` steps and at each segment end (optimised |
/// |                 | plans: the collocation knots): `t`, `q`, `v`, `tau` (held over |
/// |                 | the step that ends here), `f_n` per contact, `phase` of that step |
/// | `optimization`  | only when the optimiser ran: `status` (Ipopt's name of its |
/// |                 | return status), `iterations`, `solve_time` [s] (not with |
/// |                 | --reproducible), `cost_before`, `cost_after` (effort integral |
/// |                 | of tau^T W tau on the planner's / optimised plan), and |
/// |                 | `message` (why it failed or was rejected) when not empty |
/// | `replay`        | only when the plan was replayed (plan_replay.h): `closed_loop` |
/// |                 | {`position_error` [m], `angle_error` [rad], `min_f_n` [N], |
/// |                 | `phases`, `max_tracking_error` [rad or m], and when the part |
/// |                 | left the planned path `departure_time` [s] and |
/// |                 | `departure_phase`} and `open_loop` {the same without |
/// |                 | `max_tracking_error`} |
/// | `accepted`      | with `optimization` or `replay`: true when the optimised plan |
/// |                 | passed the replay (plan_replay.h) and is the one in the file |
/// | `planner_replay` | only when an optimised plan was not accepted: the same two |
/// |                 | replays of the plan in the file (the planner's), and `accepted`, |
/// |                 | whether that plan passes the same rule |
///
/// CSV (writePlanCsv): one row per sample, the columns of trajectory_sample.h.
/// Files are written to a temporary name and renamed; a plan with a NaN is refused.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rbsf/dynamics/phase.h"
#include "rbsf/dynamics/placement.h"
#include "rbsf/dynamics/simulator.h"
#include "rbsf/dynamics/trajectory_sample.h"
#include "rbsf/planner/certificate_report.h"

namespace rbsf::planner {

/// \brief tau held over an integer number of simulator steps.
struct PlanSegment {
  Phase phase = Phase::kC;  ///< simulated phase (majority of the steps)
  int steps = 0;            ///< simulator steps
  double duration = 0.0;    ///< steps * h [s]
  VecU tau;                 ///< order of state_layout.h (at the segment's start)
  /// \brief Empty: tau held over the segment (planner). Otherwise tau ramps linearly
  ///        from `tau` to `tau_end` (optimised plans; `steps` is then the nominal
  ///        round(duration / h) and `duration` is exact).
  VecU tau_end;
};

/// \brief How the optimiser's solve went (plan file key `optimization`).
struct OptimizationSummary {
  bool ran = false;    ///< false: --no-optimize, key not written
  std::string status;  ///< Ipopt's name of its return status, e.g. "Solve_Succeeded"
  int iterations = 0;
  double solve_time = 0.0;   ///< [s]
  double cost_before = 0.0;  ///< effort integral of tau^T W tau on the planner's plan
  double cost_after = 0.0;   ///< and on the optimised one (trajopt's EffortCost)
  std::string message;       ///< why it failed or was rejected, empty otherwise
};

/// \brief One replay of a plan in the simulator (plan file key `replay`).
struct ReplayResult {
  double position_error = 0.0;      ///< final COM distance to the goal [m]
  double angle_error = 0.0;         ///< final |phi - phi_goal|, wrapped [rad]
  double min_f_n = 0.0;             ///< least normal force over the replay [N]
  std::string phases;               ///< phase sequence seen, runs merged, e.g. "PUPU"
  double max_tracking_error = 0.0;  ///< closed loop only: max joint error [rad or m]
  /// \brief First step time t_n [s] at which the part is farther from the plan's own pose
  ///        at t_n than the replay's position or angle tolerance; -1 when it never is.
  double departure_time = -1.0;
  /// \brief The plan's phase letter (C, P or U) at departure_time; empty when none.
  std::string departure_phase;
};

/// \brief Closed- and open-loop replays of a plan and the verdict.
struct ReplaySummary {
  bool ran = false;
  ReplayResult closed_loop, open_loop;
  bool accepted = false;
};

/// \brief One point of the densely sampled trajectory (trajectory_sample.h).
using PlanSample = TrajectorySample;

/// \brief The planner's result.
struct Plan {
  std::string status = "approximate";  ///< "exact" or "approximate"
  std::string planner;
  std::uint32_t seed = 0;
  double planning_time = 0.0;
  std::uint64_t propagations = 0;
  double goal_distance = 0.0;
  /// \brief The simulator the plan was made with (time step h and tolerances): every stage
  ///        that simulates the plan (optimiser, certificate, replay) uses the same physics.
  SimulatorSettings simulator;
  int steps_per_control = 1;
  Pose start, goal;
  double start_theta = 0.0;
  VecQ q0;
  std::vector<PlanSegment> segments;
  std::vector<PlanSample> samples;
  OptimizationSummary optimization;  ///< written when optimization.ran
  ReplaySummary replay;              ///< written when replay.ran (with `accepted`)
  /// \brief The kept planner's plan's own replay (written when planner_replay.ran).
  ReplaySummary planner_replay;
  /// \brief Largest |(q, v)| difference between the planner's tree states and the plan's
  ///        re-simulation at the segment ends (not written to files).
  double path_mismatch = 0.0;

  /// \brief Total duration [s].
  double duration() const;
  /// \brief The phase letters of the segments with runs merged, e.g. "CUCU".
  std::string phaseSequence() const;
};

/// \brief Steps counted per phase over one segment, in the order C, P, U (an unsupported
///        step counts as U).
using PhaseCounts = std::array<int, 3>;

/// \brief The phase a segment is labelled with: the one most of its steps took, ties going
///        to C, then P. The one rule for the planner's segments (simulateSegments) and for
///        replays (plan_replay.h), so a plan replayed open loop shows its own labels.
Phase majorityPhase(const PhaseCounts& steps);

/// \brief Simulate `segments` from q0 at rest (fresh SimState), fill their `phase` and
///        return the samples (every `sample_steps` steps and every segment end).
///        `ends`, when given, receives the SimState at each segment end.
std::vector<PlanSample> simulateSegments(const Simulator& simulator, const VecQ& q0,
                                         std::vector<PlanSegment>& segments, int sample_steps,
                                         std::vector<SimState>* ends = nullptr);

/// \brief "C", "P", "U"; throws InputError for anything else.
Phase parsePhase(const std::string& text);

/// \brief What plan files leave out.
struct PlanFileOptions {
  /// \brief Write wall-clock measurements (`planning_time`). Off, the same seed and
  ///        settings give byte-identical files (plan-reorientation --reproducible);
  ///        readPlanJson() then reads them as 0.
  bool wall_clock = true;
};

/// \brief The JSON / CSV text of a plan. \throws std::runtime_error on a NaN.
std::string planJsonText(const Plan& plan, const PlanFileOptions& options = {});
std::string planCsvText(const Plan& plan);
/// \brief Write JSON / CSV atomically. \throws std::runtime_error on a NaN or I/O failure.
void writePlanJson(const Plan& plan, const std::string& path, const PlanFileOptions& options = {});
void writePlanCsv(const Plan& plan, const std::string& path);
/// \brief Load a plan file. \throws InputError naming the file and key when malformed.
Plan readPlanJson(const std::string& path);
/// \brief Parse plan JSON text; `label` names the source in messages.
/// \throws InputError naming the label and key when malformed.
Plan parsePlanJson(std::string_view text, const std::string& label);

}  // namespace rbsf::planner
