#pragma once
// Shared by the trajopt tests: the default cell and one short real plan (the planner's
// 15 degree turn with a fixed seed), planned once per test binary.
#include <cmath>
#include <string>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/contact_balance.h"
#include "rbsf/dynamics/core/contact_roles.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/plan.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"
#include "test_support.h"

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
    s = rbsf::test::withoutClock(s);
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

/// \brief A support plan whose roles are stated (as the support planner states them): the
///        default part held on its three tips for 0.1 s ("SSS"), then with finger 1 lifted
///        ("LSS") for 0.1 s, each under the input that holds the first (ContactBalancer);
///        the goal is where it ends. Its runs stick three tips, so the least-norm rows
///        (internal_force_constraint.h) are in the problem.
inline const plan::Plan& threeTipPlan() {
  static const plan::Plan plan = [] {
    const RbsfModel& model = defaultModel();
    plan::Plan out;
    out.status = plan::PlanStatus::kExact;
    out.planner = "support";
    out.joint_feedback = true;
    out.start = {0.1, 0.40, 0.0};
    out.q0 = restingConfiguration(model, out.start, 0.0);
    ModelData data(model.numFingers());
    const VecU tau = ContactBalancer(model).statics(out.q0, ContactSet{0b111u, 0b111u}, data).tau;
    for (const char* roles : {"SSS", "SSS", "LSS", "LSS"}) {
      plan::PlanSegment seg;
      seg.steps = 50;
      seg.duration = seg.steps * out.simulator.time_step;
      seg.tau = tau;
      seg.contacts = parseRoles(roles, model.numFingers(), "roles");
      out.segments.push_back(seg);
    }
    out.samples = plan::simulateSegments(Simulator(model, out.simulator), out.q0, out.segments, 10);
    const VecQ& end = out.samples.back().q;
    out.goal = {end[layout::kX], end[layout::kY], end[layout::kPhi]};
    return out;
  }();
  return plan;
}

}  // namespace rbsf::trajopt::test
