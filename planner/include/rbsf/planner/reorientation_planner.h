#pragma once
/// \file
/// \brief The reorientation planner: from the part at rest on the fingers to a goal pose,
///        tau segments found by an OMPL control planner with the simulator as propagator.
///
/// Setup (solve()):
///   - state space SimStateSpace (state_space.h), projection (phi, theta) (projection.h);
///   - control space: tau in R^(m+1) within the cell's limits; propagation step
///     k = steps_per_control simulator steps, control durations min_control_steps ..
///     max_control_steps propagation steps; controls from PhaseControlSampler;
///   - propagator SimPropagator (with the decisive-modes rule, propagator.h), validity
///     SupportValidityChecker (which refuses what that rule marks), goal PoseGoal;
///   - planner by name (plannerNames()): KPIECE1 (default), RRT, SST, EST, PDST,
///     single-threaded; ompl::RNG::setSeed(seed) before anything is created, so the same
///     seed and settings give the same plan when the search ends by reaching the goal.
/// setup() builds these OMPL objects (planner_setup.h) for the benchmark tool; solve()
/// seeds OMPL, runs the same setup and turns its solution into a Plan with makePlan().
/// The search stops at the goal or at the time limit. The returned plan is the solution
/// path's controls re-simulated from the start (plan.h), with each segment's simulated
/// phase; path_mismatch compares that re-simulation with the planner's own states.
/// OMPL's console output is silenced.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rbsf/dynamics/simulator.h"
#include "rbsf/planner/control_sampler.h"
#include "rbsf/planner/plan.h"
#include "rbsf/planner/planner_setup.h"
#include "rbsf/planner/propagator.h"
#include "rbsf/planner/state_space.h"
#include "rbsf/planner/validity.h"

namespace rbsf::planner {

/// \brief Progress during the search (reported about once per second).
struct Progress {
  double elapsed = 0.0;  ///< [s]
  std::uint64_t propagations = 0;
  double best_distance = 0.0;  ///< goal distance in tolerance units (<= 1: reached)
};

/// \brief Everything the planner can be told.
struct PlannerSettings {
  std::string planner = "KPIECE1";
  double time_limit = 30.0;  ///< [s]
  std::uint32_t seed = 1;
  double position_tolerance = 0.01;           ///< [m]
  double angle_tolerance = 2.0 * M_PI / 180;  ///< [rad]
  SimulatorSettings simulator;
  int steps_per_control = 20;    ///< simulator steps per propagation step
  int min_control_steps = 1;     ///< propagation steps per control, least
  int max_control_steps = 10;    ///< and most
  int sample_steps = 10;         ///< simulator steps between plan samples
  double projection_cell = 0.1;  ///< [rad], both projection axes
  double goal_bias = 0.05;
  SpeedBounds speed;
  ValiditySettings validity;
  DecisiveModes decisive_modes;  ///< propagation steps a tracking cell repeats (propagator.h)
  SamplerSettings sampler;
  std::function<void(const Progress&)> progress;  ///< called about once per second
  /// \brief When set and it becomes true (another thread, a signal handler), the search
  ///        stops at its next check and solve() returns the best plan found so far.
  const std::atomic<bool>* cancel = nullptr;
};

/// \brief The problem: start pose (fingers placed at start_theta, part at rest) and goal.
struct Problem {
  Pose start;
  double start_theta = 0.0;
  Pose goal;
  /// \brief false: the goal angle is a pose, reached whichever way the part turns (phi
  ///        compared modulo 2 pi, so 270 deg is -90 deg). true: the goal angle is the
  ///        part's total turn from phi = 0 (phi is never wrapped along a motion), so a
  ///        start at 0 and a goal at -270 deg asks for three quarters of a clockwise turn.
  bool absolute_angle = false;
};

/// \brief Planner names accepted by PlannerSettings::planner.
const std::vector<std::string>& plannerNames();

/// \brief The planner for one cell.
class ReorientationPlanner {
 public:
  /// \throws InputError for an unknown planner name or bad settings.
  ReorientationPlanner(const RbsfModel& model, PlannerSettings settings);

  /// \brief The start configuration of `problem`, checked: fingers placed by the placement
  ///        rule at start_theta and the part holdable at rest within the limits; the goal
  ///        reachable: at some base angle within the base range at least
  ///        validity.min_touching fingers' lines of travel enter the part within their
  ///        strokes. \throws InputError saying which and why.
  VecQ checkProblem(const Problem& problem) const;

  /// \brief Search. Returns false (and leaves `plan` empty) only when the planner produced
  ///        no path at all; otherwise plan.status says "exact" or "approximate".
  bool solve(const Problem& problem, Plan& plan);

  /// \brief The OMPL setup for `problem` (checked with checkProblem()); OMPL not seeded.
  PlannerSetup setup(const Problem& problem) const;

  /// \brief The plan of a setup's solution path: its controls re-simulated from q0, with
  ///        path_mismatch against the planner's states and the goal distance of the
  ///        re-simulated end. Returns false (plan untouched) when there is no path.
  bool makePlan(const Problem& problem, const PlannerSetup& setup, double planning_time,
                Plan& plan) const;

  /// \brief Smallest goal distance reached by the last solve() (tolerance units).
  double bestDistance() const { return best_distance_; }
  /// \brief Propagations of the last solve().
  std::uint64_t propagations() const { return propagations_; }

  const Simulator& simulator() const { return simulator_; }
  const PlannerSettings& settings() const { return settings_; }

 private:
  const RbsfModel& model_;
  PlannerSettings settings_;
  Simulator simulator_;
  double best_distance_ = 0.0;
  std::uint64_t propagations_ = 0;
};

}  // namespace rbsf::planner
