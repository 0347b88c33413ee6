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
/// | `feedback`      | `"joints"` when the plan holds the part by the joints alone (its |
/// |                 | law feeds back the joints only); absent otherwise |
/// | `start`, `goal` | poses {x, y, phi}; `start_theta` the base angle at the start |
/// | `q0`            | start configuration (state_layout.h order), at rest |
/// | `phase_sequence` | the segments' phases, runs merged (Plan::phaseSequence) |
/// | `segments[]`    | `phase` ("C", "P" or "U": the phase most steps of the segment |
/// |                 | took in simulation), `duration` [s], `steps`, `tau`; `tau_end` |
/// |                 | only for a ramp (optimised plans): tau goes linearly from `tau` |
/// |                 | to `tau_end` over the segment; `contacts`: each finger's role |
/// |                 | over the segment (contact_roles.h: "LS+" = finger 1 lifted, 2 |
/// |                 | sticking, 3 sliding in +t), the planner's where it states them, |
/// |                 | else what most of the segment's simulated steps did |
/// | `samples[]`     | every `sample_steps` steps and at each segment end (optimised |
/// |                 | plans: the collocation knots): `t`, `q`, `v`, `tau` (held over |
/// |                 | the step that ends here), `f_n` per contact, `phase` of that step |
/// | `optimization`  | only when the optimiser ran: `status` (Ipopt's name of its |
/// |                 | return status), `iterations`, `solve_time` [s] (not with |
/// |                 | --reproducible), `cost_before`, `cost_after` (effort integral |
/// |                 | of tau^T W tau on the planner's / optimised plan), `chosen` |
/// |                 | (true: the plan in the file is the optimised one), |
/// |                 | `refined_success_rate` (the optimised plan's certificate, when |
/// |                 | it ran) and `message` (why it failed or was not chosen) |
/// | `certificate`   | when the plan was certified (certificate.h): `law`, `trials` |
/// |                 | (run and counted), `successes`, `success_rate`, `lower_bound` |
/// |                 | (the one-sided Clopper-Pearson lower bound of the rate, |
/// |                 | confidence.h; checked against the counts on reading), |
/// |                 | `confidence`, `required_rate`, `certified` (`lower_bound` >= |
/// |                 | `required_rate`, and the motion and holding checks), |
/// |                 | `sequential` (`false` for a fixed count, else {`batch`, |
/// |                 | `max_trials`}), |
/// |                 | `seed`, `criteria` {`position_tolerance` [m], `angle_tolerance` |
/// |                 | [rad], `rest_speed` [m/s], `rest_angular_speed` [rad/s], |
/// |                 | `settle_time` [s]}, the `sensing` and `uncertainty` used (cell |
/// |                 | file keys), and the `worst` trial: `trial`, `success`, |
/// |                 | `failure`, `position_error` [m], `angle_error` [rad], `speed` |
/// |                 | [m/s], `angular_speed` [rad/s], `dropped` (and `dropped_time`), |
/// |                 | `saturated_time` [s], `min_f_n` [N], `max_deviation` |
/// |                 | [tolerance units], `phases`, and where it left the planned |
/// |                 | path `departure_time` [s], `departure_phase`; `motion` (when |
/// |                 | the plan has samples, plan_motion.h): `peak_speed` [m/s] and |
/// |                 | `peak_speed_time` [s], `peak_angular_speed` [rad/s] and |
/// |                 | `peak_angular_time`, `end_speed`, `end_angular_speed` and the |
/// |                 | cell's `limits` {`part_speed`, `angular_speed`, `rest`}; |
/// |                 | `holding` (under the joint law, plan_holding.h): `measured`, |
/// |                 | `free_time`, `longest_free`, `longest_free_start`, |
/// |                 | `max_free_time` [s] |
///
/// CSV (writePlanCsv): one row per sample, the columns of trajectory_sample.h.
/// Files are written to a temporary name and renamed; a plan with a NaN is refused.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rbsf/dynamics/cell.h"
#include "rbsf/dynamics/contact_roles.h"
#include "rbsf/dynamics/phase.h"
#include "rbsf/dynamics/placement.h"
#include "rbsf/dynamics/simulator.h"
#include "rbsf/dynamics/trajectory_sample.h"
#include "rbsf/plan/certificate_report.h"

namespace rbsf::plan {

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
  /// \brief Each contact's role over the segment (contact_roles.h); kUnplanned until the
  ///        planner or simulateSegments states it.
  ContactRoles contacts{};
};

/// \brief How the optimiser's solve went (plan file key `optimization`).
struct OptimizationSummary {
  bool ran = false;    ///< false: --no-optimize, key not written
  std::string status;  ///< Ipopt's name of its return status, e.g. "Solve_Succeeded"
  int iterations = 0;
  double solve_time = 0.0;   ///< [s]
  double cost_before = 0.0;  ///< effort integral of tau^T W tau on the planner's plan
  double cost_after = 0.0;   ///< and on the optimised one (trajopt's EffortCost)
  bool chosen = false;       ///< the plan in the file is the optimised one
  /// \brief Success rate of the optimised plan's certificate; -1 when it was not certified.
  double refined_success_rate = -1.0;
  std::string message;  ///< why it failed or was not chosen, empty otherwise
};

/// \brief One point of the densely sampled trajectory (trajectory_sample.h).
using PlanSample = TrajectorySample;

/// \brief Whether a plan reaches its goal: kExact when its end is within the goal's
///        tolerances, kApproximate for the closest a search came.
enum class PlanStatus { kExact, kApproximate };

/// \brief "exact" or "approximate", the words of the plan file and the outputs.
std::string_view toString(PlanStatus status);

/// \brief What a plan records of the cell it was made for (plan file key `cell`), so that a
///        cell controller refuses it on another cell (plan_fit.h). The part's shape is not
///        recorded: the plan's start placement q0 checks it.
struct PlanCell {
  bool recorded = false;         ///< false: no `cell` key (plans written before it existed)
  std::vector<double> finger_r;  ///< each finger's lateral offset r_i [m]
  double part_mass = 0.0;        ///< m_o [kg]
  double part_inertia = 0.0;     ///< I_o [kg m^2]
  double gravity = 0.0;          ///< g0 [m/s^2]
};

/// \brief The record of `cell` a plan carries.
PlanCell planCell(const Cell& cell);

/// \brief The planner's result.
struct Plan {
  PlanStatus status = PlanStatus::kApproximate;
  std::string planner;
  std::uint32_t seed = 0;
  double planning_time = 0.0;
  std::uint64_t propagations = 0;
  double goal_distance = 0.0;
  /// \brief The simulator the plan was made with (time step h and tolerances): every stage
  ///        that simulates the plan (optimiser, certificate, replay) uses the same physics.
  SimulatorSettings simulator;
  int steps_per_control = 1;
  /// \brief The plan holds the part by the joints alone at every step (support_search.h):
  ///        its law feeds back the joints only, whatever the cell senses (lawSensing()).
  bool joint_feedback = false;
  Pose start, goal;
  double start_theta = 0.0;
  VecQ q0;
  PlanCell cell;  ///< the cell it was made for (written when recorded)
  std::vector<PlanSegment> segments;
  std::vector<PlanSample> samples;
  OptimizationSummary optimization;  ///< written when optimization.ran
  Certificate certificate;           ///< written when certificate.ran
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
///        to C, then P (the planner's segments, simulateSegments).
Phase majorityPhase(const PhaseCounts& steps);

/// \brief Simulate `segments` from q0 at rest (fresh SimState), fill their `phase` and,
///        where the planner did not state them, their `contacts` (the roles most of the
///        segment's steps gave each contact, contact_roles.h roleOf with `min_force` [N]),
///        and return the samples (every `sample_steps` steps and every segment end).
///        `ends`, when given, receives the SimState at each segment end.
std::vector<PlanSample> simulateSegments(const Simulator& simulator, const VecQ& q0,
                                         std::vector<PlanSegment>& segments, int sample_steps,
                                         std::vector<SimState>* ends = nullptr,
                                         double min_force = 0.0);

/// \brief Phase letters of consecutive runs (phase, duration [s]): runs shorter than
///        `min_run` dropped, then equal neighbours merged. When every run is short the
///        longest one is kept (a sequence is never empty for a non-empty input).
std::string filterPhaseRuns(const std::vector<std::pair<Phase, double>>& runs, double min_run);

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

}  // namespace rbsf::plan
