// Uses the installed rbsf package: loads a cell, plans a short turn (30 degrees) and
// samples the plan. Exit status 0 when an exact plan was found and re-simulating its
// segments reproduces its samples.
#include <cmath>
#include <cstdio>
#include <exception>

#include <rbsf/dynamics/cell.h>
#include <rbsf/dynamics/model.h>
#include <rbsf/dynamics/state_layout.h>
#include <rbsf/planner/reorientation_planner.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: rbsf_consumer CELL.yaml\n");
    return 2;
  }
  try {
    const rbsf::RbsfModel model(rbsf::loadCell(argv[1]));
    rbsf::planner::PlannerSettings settings;
    settings.time_limit = 60.0;
    rbsf::planner::ReorientationPlanner planner(model, settings);
    const double turn = -30.0 * M_PI / 180.0;
    const rbsf::planner::Problem problem{{0.1, 0.40, 0.0}, 0.0, {0.1, 0.40, turn}};
    rbsf::planner::Plan plan;
    if (!planner.solve(problem, plan) || plan.status != "exact") {
      std::fprintf(stderr, "rbsf_consumer: no exact plan (best distance %g)\n",
                   planner.bestDistance());
      return 1;
    }
    const auto& last = plan.samples.back();
    std::printf("plan: %zu segments, %.3f s, phases %s, final phi %.4f rad (goal %.4f)\n",
                plan.segments.size(), plan.duration(), plan.phaseSequence().c_str(),
                last.q[rbsf::layout::kPhi], turn);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rbsf_consumer: %s\n", e.what());
    return 1;
  }
}
