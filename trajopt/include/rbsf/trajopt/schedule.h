#pragma once
/// \file
/// \brief The phase schedule the optimiser keeps: the plan's phase runs, each contact's
///        role in each run, and how the collocation intervals are spread over the runs.

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/contact_roles.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/plan/plan.h"

namespace rbsf::trajopt {

/// \brief What a contact does over a whole run.
enum class ContactRole { kOff, kSlide, kStick };

/// \brief One run of plan segments merged: one phase letter (and, when split by contact
///        modes, one simulated mode per contact; buildSchedule).
struct PhaseRun {
  Phase phase = Phase::kC;
  double duration = 0.0;  ///< planned duration [s]
  double start = 0.0;     ///< planned start time [s]
  int first_interval = 0;
  int intervals = 0;
  std::array<ContactRole, kMaxFingers> role{};
  /// \brief Sign (+1, -1, 0) of the planned change of xi over the run, per contact.
  std::array<int, kMaxFingers> slide_direction{};
  /// \brief Planned mean |d xi / dt| over the run, per sliding contact [1/s].
  std::array<double, kMaxFingers> slide_rate{};
  /// \brief The plan relies on the contact (stated S, + or -; without stated roles every
  ///        contact that is not off): its normal force keeps the optimiser's floor.
  std::array<bool, kMaxFingers> relied{};
  /// \brief The roles the plan states over the run (contact_roles.h); kUnplanned when the
  ///        plan does not state them.
  rbsf::ContactRoles planned{};
  /// \brief The part rests throughout the run in the re-simulation: its speeds at every
  ///        step within 10 x the cell's motion_limits rest (motion_limits.h), so that a
  ///        closed-loop run settling into its end rest counts.
  bool at_rest = false;
};

/// \brief The plan re-simulated step by step, as buildSchedule saw it (the initial guess
///        reads it too, so the plan is simulated once per problem).
struct SimulatedSteps {
  std::vector<double> t;   ///< t[j]: end of step j - 1, t[0] = 0 [s]
  std::vector<VecQ> q, v;  ///< state at t[j]
  /// \brief Contact reports of step j (from t[j] to t[j + 1]): mode, mean f_n, f_t [N].
  std::vector<std::array<ContactStepReport, kMaxFingers>> contacts;
};

/// \brief Runs and the interval -> run map.
struct Schedule {
  std::vector<PhaseRun> runs;
  std::vector<int> run_of_interval;  ///< size N
  SimulatedSteps steps;              ///< the re-simulation the runs were read from

  int intervals() const { return static_cast<int>(run_of_interval.size()); }
  const PhaseRun& runOf(int interval) const { return runs[run_of_interval[interval]]; }
  /// \brief Role of contact i on interval k.
  ContactRole role(int interval, int i) const { return runOf(interval).role[i]; }
  /// \brief Role of contact i at knot k: the "strongest" of its adjacent intervals
  ///        (stick > slide > off), so a knot between an on and an off run is on.
  ContactRole knotRole(int knot, int i) const;
  /// \brief Role of contact i for knot k's forces: that of the interval the knot starts
  ///        (the last knot: the last interval's), so a force acts from where a mode begins.
  ContactRole forceRole(int knot, int i) const { return role(std::min(knot, intervals() - 1), i); }
};

/// \brief Where buildSchedule cuts the plan into runs.
enum class RunCut {
  kPhaseLetters,  ///< where the segments' phase letter changes
  kContactModes,  ///< also where a contact's simulated majority mode changes
  kStatedRoles,   ///< where the roles the plan states change (contact_roles.h)
};

/// \brief What buildSchedule gives: the schedule, or why the plan gives none.
struct ScheduleResult {
  Schedule schedule;  ///< the runs and their intervals; empty when not ok()
  std::string error;  ///< why there is no schedule; empty when ok()
  /// \brief Whether the schedule was built (no error).
  bool ok() const { return error.empty(); }
};

/// \brief Re-simulate the plan's segments (with the plan's simulator settings) and group
///        them into runs. RunCut::kStatedRoles (a plan whose segments all state their
///        contacts' roles, as support plans do) cuts where the roles change and keeps them:
///        S sticks, + and - slide (the way the re-simulation slid), F sticks without being
///        relied on (PhaseRun::relied false: no normal floor), L is off; the letter follows
///        the sticking count. Otherwise runs are consecutive segments of one phase letter
///        and, with kContactModes, the same majority mode of every contact over the segment
///        (a P run in which a third finger lands becomes two P runs); when that gives more
///        than intervals / 2 runs, by letter alone. Count each contact's mode per run and
///        pick its role by majority, then make it agree with the run's letter: C at least two
///        sticking (the most sticking ones), P exactly the one that sticks most, U none
///        sticking (a sticking majority becomes sliding). Spread `intervals` over the runs in
///        proportion to their durations, at least 2 each.
/// \return the schedule, or an error when the plan has no segments, a segment holds no
///         simulator step, kStatedRoles meets a segment that states no roles, or intervals
///         < 2 runs.
ScheduleResult buildSchedule(const RbsfModel& model, const plan::Plan& plan, int intervals,
                             RunCut cut);

}  // namespace rbsf::trajopt
