#pragma once
/// \file
/// \brief A plan file: the plan with the evidence it travels with, its optimisation summary
///        and its certificate (PlanRecord), as JSON.
///
/// JSON (writePlanJson / readPlanJson; keys in this order; `optimization` and `certificate`
/// are the record's, the rest the plan's):
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
/// Files are written to a temporary name and renamed; a plan with a NaN is refused.

#include <string>
#include <string_view>

#include "rbsf/plan/certificate_report.h"
#include "rbsf/plan/optimization_summary.h"
#include "rbsf/plan/plan.h"

namespace rbsf::plan {

/// \brief A plan and what was learnt of it: how its optimisation went and its certificate
///        (closed-loop trials, certificate.h). What the pipeline returns, the controller
///        publishes and a plan file holds.
struct PlanRecord {
  Plan plan;
  OptimizationSummary optimization;  ///< written when optimization.ran
  Certificate certificate;           ///< written when certificate.ran
};

/// \brief What plan files leave out.
struct PlanFileOptions {
  /// \brief Write wall-clock measurements (`planning_time`, `solve_time`). Off, the same
  ///        seed and settings give byte-identical files (plan-reorientation
  ///        --reproducible); readPlanJson() then reads them as 0.
  bool wall_clock = true;
};

/// \brief The JSON text of a record. \throws std::runtime_error on a NaN.
std::string planJsonText(const PlanRecord& record, const PlanFileOptions& options = {});
/// \brief Write the JSON atomically. \throws std::runtime_error on a NaN or I/O failure.
void writePlanJson(const PlanRecord& record, const std::string& path,
                   const PlanFileOptions& options = {});
/// \brief Load a plan file. \throws InputError naming the file and key when malformed.
PlanRecord readPlanJson(const std::string& path);
/// \brief Parse plan JSON text; `label` names the source in messages.
/// \throws InputError naming the label and key when malformed.
PlanRecord parsePlanJson(std::string_view text, const std::string& label);

}  // namespace rbsf::plan
