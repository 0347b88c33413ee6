// Planner benchmark (not a timed test): the default cell's 30, 90 and 180 degree
// reorientations over seeds 1..N with KPIECE1 (or --planner); success rate (exact within
// the time limit), median and worst planning time, propagations per second.
//   build/bench/rbsf_planner_bench [--seeds 20] [--time-limit 30] [--planner KPIECE1]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "rbsf/dynamics/cell.h"
#include "rbsf/planner/reorientation_planner.h"

int main(int argc, char** argv) {
  int seeds = 20;
  double time_limit = 30.0;
  std::string name = "KPIECE1";
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--seeds")) seeds = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--time-limit")) time_limit = std::atof(argv[k + 1]);
    if (!std::strcmp(argv[k], "--planner")) name = argv[k + 1];
  }
  const rbsf::RbsfModel model(rbsf::loadCell(RBSF_SOURCE_DIR "/cells/default.yaml"));
  struct Case {
    const char* label;
    rbsf::Pose goal;
  };
  const double deg = M_PI / 180.0;
  const Case cases[] = {{"30 deg", {0.1, 0.40, -30 * deg}},
                        {"90 deg", {-0.1, 0.40, -90 * deg}},
                        {"180 deg", {-0.1, 0.40, 180 * deg}}};
  std::printf("%-8s %-8s %6s %10s %10s %14s %s\n", "problem", "planner", "exact", "median[s]",
              "worst[s]", "propagations/s", "(seeds 1..N, time limit per seed)");
  for (const Case& c : cases) {
    std::vector<double> times;
    int exact = 0;
    double props = 0.0, total_time = 0.0;
    for (int seed = 1; seed <= seeds; ++seed) {
      rbsf::planner::PlannerSettings s;
      s.planner = name;
      s.seed = static_cast<std::uint32_t>(seed);
      s.time_limit = time_limit;
      rbsf::planner::ReorientationPlanner planner(model, s);
      rbsf::planner::Problem p;
      p.start = {0.1, 0.40, 0.0};
      p.goal = c.goal;
      rbsf::planner::Plan plan;
      const bool found = planner.solve(p, plan);
      const bool ok = found && plan.status == "exact";
      exact += ok;
      times.push_back(ok ? plan.planning_time : INFINITY);
      props += static_cast<double>(planner.propagations());
      total_time += found ? plan.planning_time : time_limit;
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    std::printf("%-8s %-8s %3d/%-3d %10.3f %10.3f %14.0f\n", c.label, name.c_str(), exact, seeds,
                median, times.back(), props / total_time);
    std::fflush(stdout);
  }
  return 0;
}
