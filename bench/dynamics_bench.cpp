// One full acceleration-level evaluation (state and tau in; contact points, F_n and
// accelerations out): forwardDynamicsU for m = 2, 3, 4, 6, 8 fingers, every contact
// touching, the part at rest on the fingers with a holding-like input. The cells are the
// test cells of tests/unit/test_support.h (the default part on m fingers).
#include <benchmark/benchmark.h>

#include "../tests/unit/test_support.h"

#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {
namespace {

void BM_ForwardDynamicsU(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, m));
  const VecQ q = restingConfiguration(model, Pose{0.10, 0.40, 0.05}, 0.1);
  VecQ v = VecQ::Zero(m + 4);
  v[layout::kTheta] = 0.2;
  v[layout::kPhi] = 0.1;
  VecU tau = VecU::Constant(m + 1, 80.0);
  tau[layout::kTauTheta] = 10.0;
  ModelData data(m);
  forwardDynamicsU(model, q, v, tau, data);
  for (auto _ : state) {
    forwardDynamicsU(model, q, v, tau, data);
    benchmark::DoNotOptimize(data.vdot.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ForwardDynamicsU)->Arg(2)->Arg(3)->Arg(4)->Arg(6)->Arg(8);

}  // namespace
}  // namespace rbsf
