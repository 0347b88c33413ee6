// The control sampler's inverse dynamics by phase (planner/phase_targets.h) at the default
// part resting on the default cell:
//   StickTau: tau for a phase C target (base and common stroke accelerations);
//   SlideTau: tau for a phase U target (object and base accelerations).
#include <benchmark/benchmark.h>

#include <string>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/kinodynamic/phase_targets.h"

namespace rbsf {
namespace {

struct TargetsFixture {
  RbsfModel model{loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml")};
  planner::PhaseTargeting targeting{model, 1e-3};
  VecQ q = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  VecQ v = VecQ::Zero(model.configDim());
  VecU tau = VecU::Zero(model.controlDim());
};

void BM_StickTau(benchmark::State& state) {
  TargetsFixture f;
  const planner::StickTarget target{0.5, 0.1};
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.targeting.stickTau(f.q, f.v, target, f.tau));
    benchmark::DoNotOptimize(f.tau.data());
  }
}
BENCHMARK(BM_StickTau);

void BM_SlideTau(benchmark::State& state) {
  TargetsFixture f;
  planner::SlideTarget target;
  target.accel_x = 0.2;
  target.omega_dot = 1.0;
  target.base_accel = 0.5;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.targeting.slideTau(f.q, f.v, target, f.tau));
    benchmark::DoNotOptimize(f.tau.data());
  }
}
BENCHMARK(BM_SlideTau);

}  // namespace
}  // namespace rbsf
