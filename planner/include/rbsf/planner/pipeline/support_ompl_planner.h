#pragma once
/// \file
/// \brief The support planner (support_planner.h) as an OMPL planner, so that OMPL's
///        Benchmark (rbsf-bench, Planner Arena) runs it beside KPIECE1 on the same setup
///        (planner_setup.h).
///
/// solve() reads the start state (SimStateSpace: the part's pose and the base angle) and the
/// goal (PoseGoal: the pose and its tolerances), runs SupportPlanner::solve, which stops when
/// the termination condition fires, and adds its plan as an ompl::control::PathControl: one
/// control per plan segment (tau held over the segment; a last segment shorter than a
/// control, for a whole one), the states propagated by the setup's
/// state propagator from the plan's start configuration (a support plan is exact: its
/// segments re-simulated reproduce it). That configuration has the start state's part pose
/// and base angle; the fingers the plan's first support lifts are at their lower stroke
/// limits, where the start state has every finger placed. So the propagation step must be the
/// plan's control period (kControlSteps simulator steps) and the propagator a SimPropagator
/// without the decisive-modes rule (a device of the kinodynamic search that would cut the
/// plan's steps short): setup() refuses another.
///
/// Status: EXACT_SOLUTION when the plan's closed-loop run ends on the goal,
/// APPROXIMATE_SOLUTION when the plan kept does not (the run that followed its reference
/// longest), TIMEOUT when the condition or the expansion budget stopped the searches before
/// a path, ABORT when every search was exhausted without one (OMPL 1.5 has no INFEASIBLE;
/// reach() says what they reached). Settings are
/// SupportPlannerSettings; the termination condition replaces its time limit.

#include <memory>

#include <ompl/base/Planner.h>
#include <ompl/control/SpaceInformation.h>

#include "rbsf/plan/plan_margins.h"
#include "rbsf/planner/support/support_planner.h"

namespace rbsf::planner {

/// \brief SupportPlanner behind ompl::base::Planner (file comment).
class SupportOmplPlanner : public ompl::base::Planner {
 public:
  /// \brief Simulator steps per control of a support plan (closedLoopPlan's law period).
  static constexpr int kControlSteps = 5;

  SupportOmplPlanner(const ompl::control::SpaceInformationPtr& si, const RbsfModel& model,
                     SupportPlannerSettings settings = SupportPlannerSettings());

  /// \brief Checks the goal's type and the propagation step; on failure setup stays false
  ///        and solve() says why.
  void setup() override;
  /// \brief Forgets the last plan (OMPL's Benchmark calls it between runs).
  void clear() override;
  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;

  /// \brief The plan of the last solve() (empty when none).
  const plan::Plan& lastPlan() const { return plan_; }
  /// \brief Expansions of the last solve(), every search.
  long expansions() const { return expansions_; }
  /// \brief What the last solve()'s searches reached (support_reach.h).
  const SupportReach& reach() const { return reach_; }
  /// \brief The margins the last plan was planned with (its refinement keeps them).
  const plan::PlanMargins& margins() const { return margins_; }
  SupportPlannerSettings& settings() { return settings_; }

 private:
  ompl::control::SpaceInformation* siC_;
  const RbsfModel& model_;
  SupportPlannerSettings settings_;
  plan::Plan plan_;
  long expansions_ = 0;
  SupportReach reach_;
  plan::PlanMargins margins_;
};

}  // namespace rbsf::planner
