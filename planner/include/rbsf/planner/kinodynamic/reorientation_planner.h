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
///   - planner (KinodynamicPlanner): KPIECE1 (default), RRT, SST, EST, PDST,
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

#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/plan/plan.h"
#include "rbsf/planner/kinodynamic/control_sampler.h"
#include "rbsf/planner/kinodynamic/planner_setup.h"
#include "rbsf/planner/kinodynamic/propagator.h"
#include "rbsf/planner/kinodynamic/state_space.h"
#include "rbsf/planner/kinodynamic/validity.h"
#include "rbsf/planner/planner_settings.h"

namespace rbsf::planner {

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

  /// \brief Search until the goal, the budget or `context`'s cancel. Returns false (and
  ///        leaves `plan` empty) only when the planner produced no path at all; otherwise
  ///        plan.status says "exact" or "approximate".
  bool solve(const Problem& problem, plan::Plan& plan, const SearchContext& context = {});

  /// \brief The OMPL setup for `problem` (checked with checkProblem()); OMPL not seeded.
  PlannerSetup setup(const Problem& problem) const;

  /// \brief The plan of a setup's solution path: its controls re-simulated from q0, with
  ///        path_mismatch against the planner's states and the goal distance of the
  ///        re-simulated end. Returns false (plan untouched) when there is no path.
  bool makePlan(const Problem& problem, const PlannerSetup& setup, double planning_time,
                plan::Plan& plan) const;

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
