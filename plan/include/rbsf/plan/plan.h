#pragma once
/// \file
/// \brief A plan: tau segments, the trajectory they produce, and its files.
///
/// The plan file (JSON, with its certificate and optimisation summary) is plan_file.h.
///
/// CSV (writePlanCsv): one row per sample, the columns of trajectory_sample.h.
/// Files are written to a temporary name and renamed; a plan with a NaN is refused.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/contact_roles.h"
#include "rbsf/dynamics/core/phase.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/trajectory_sample.h"

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
  /// \brief The friction it was planned and certified with (mu_s, mu_k); false: not in
  ///        the file (plans written before it was).
  bool friction_recorded = false;
  double mu_static = 0.0;
  double mu_kinetic = 0.0;
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
  /// \brief Largest |(q, v)| difference between the planner's tree states and the plan's
  ///        re-simulation at the segment ends (not written to files).
  double path_mismatch = 0.0;

  /// \brief Total duration [s].
  double duration() const;
  /// \brief The phase letters of the segments with runs merged, e.g. "CUCU".
  std::string phaseSequence() const;
  /// \brief The phases the segments' roles plan (contact_roles.h), runs merged: P where some
  ///        contact is planned to slide beside exactly one that sticks, U where some slides
  ///        and none sticks, C elsewhere (at rest, rigid, hand-overs), e.g. "CPCPC". The
  ///        simulated phases (phaseSequence) may flicker where a slider sticks for a step.
  std::string plannedPhases() const;
  /// \brief The pivots of the plan: the runs of P in plannedPhases().
  int pivots() const;
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

/// \brief The CSV text of a plan. \throws std::runtime_error on a NaN.
std::string planCsvText(const Plan& plan);
/// \brief Write the CSV atomically. \throws std::runtime_error on a NaN or I/O failure.
void writePlanCsv(const Plan& plan, const std::string& path);

}  // namespace rbsf::plan
