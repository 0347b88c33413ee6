// The support search's costs (planner/support_search.h) on the default cell:
//   EllipseEntry/0: the default part's line entry by the closed-form quadratic;
//   EllipseEntry/1: the same by the generic boundary scan (Shape::entryAlongLine);
//   SupportCheck: one balanced-support check (configuration, balance LP, determination)
//                 of the part resting on three sliding tips;
//   SupportSearch: the 90 degree problem's search for its first 5000 expansions
//                  (5 deg / 2 cm lattice, friction use 0.6), per search.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/support/support_planner.h"
#include "rbsf/planner/support/support_search.h"

namespace rbsf {
namespace {

const RbsfModel& defaultModel() {
  static const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  return model;
}

void BM_EllipseEntry(benchmark::State& state) {
  const Shape& shape = defaultModel().shape();
  const bool scan = state.range(0) == 1;
  double s = 0.0, xi = 0.0, x = -0.25;
  for (auto _ : state) {
    x = x > 0.25 ? -0.25 : x + 0.01;  // vertical finger lines across the part
    const Vec2 origin(x, -1.0), dir(0.0, 1.0);
    benchmark::DoNotOptimize(scan ? shape.Shape::entryAlongLine(origin, dir, s, xi)
                                  : shape.entryAlongLine(origin, dir, s, xi));
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_EllipseEntry)->Arg(0)->Arg(1);

void BM_SupportCheck(benchmark::State& state) {
  planner::SupportGeometry geometry(defaultModel(),
                                    planner::SupportPlannerSettings::defaultSearch().support);
  const planner::JigPose pose = planner::JigPose::fromWorld(Pose{0.1, 0.40, 0.0}, 0.0);
  const ContactSet set{0b111u, 0u};
  for (auto _ : state) benchmark::DoNotOptimize(geometry.check(pose, set).valid);
}
BENCHMARK(BM_SupportCheck);

void BM_SupportSearch(benchmark::State& state) {
  planner::SupportSearchSettings settings = planner::SupportPlannerSettings::defaultSearch();
  settings.support.balance.friction_use = 0.6;
  settings.max_expansions = 5000;
  settings.time_limit = 600.0;
  for (auto _ : state) {
    planner::SupportSearch search(defaultModel(), settings);
    const planner::SupportPath path =
        search.search(Pose{0.1, 0.40, 0.0}, 0.0, Pose{-0.1, 0.40, -M_PI / 2});
    benchmark::DoNotOptimize(path.expansions);
  }
}
BENCHMARK(BM_SupportSearch)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rbsf
