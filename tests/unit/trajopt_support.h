#pragma once
// Shared by the trajopt tests: the default cell and one short real plan (the planner's
// 15 degree turn with a fixed seed), planned once per test binary.
#include <cmath>
#include <string>

#include "rbsf/dynamics/cell.h"
#include "rbsf/planner/reorientation_planner.h"

namespace rbsf::trajopt::test {

inline const RbsfModel& defaultModel() {
  static const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  return model;
}

/// \brief The planner's plan of a 15 degree turn (seed 5: phases C, P, U), planned once.
///        The motion limits are off: the derivatives are checked on a short plan of three
///        phase runs, which the seed gives without them.
inline const plan::Plan& shortPlan() {
  static const plan::Plan plan = [] {
    planner::PlannerSettings s;
    s.seed = 5;
    s.time_limit = 3600.0;
    s.max_propagations = 200000;
    s.keep_motion_limits = false;
    planner::ReorientationPlanner planner(defaultModel(), s);
    planner::Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
    plan::Plan out;
    if (!planner.solve(p, out)) throw std::runtime_error("planner failed on the 15 degree turn");
    return out;
  }();
  return plan;
}

}  // namespace rbsf::trajopt::test
