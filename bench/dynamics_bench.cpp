// One full acceleration-level evaluation (state and tau in; contact points, F_n and
// accelerations out): forwardDynamicsU for m = 2, 3, 4, 6, 8 fingers, every contact
// touching, the part at rest on the fingers with a holding-like input.
#include <benchmark/benchmark.h>

#include <memory>

#include "rbsf/dynamics/forward_dynamics.h"
#include "rbsf/dynamics/placement.h"
#include "rbsf/dynamics/state_layout.h"

namespace rbsf {
namespace {

Cell benchCell(int m) {
  Cell c;
  c.base = {5.0, -0.785398, 0.785398, 400.0};
  for (int i = 0; i < m; ++i) {
    FingerParams f;
    f.r = m == 1 ? 0.0 : -0.20 + 0.40 * i / (m - 1);
    f.stroke_min = 0.05;
    f.stroke_max = 0.55;
    f.mass = 2.0;
    f.force_limit = 800.0;
    c.fingers.push_back(f);
  }
  c.object.shape = std::make_shared<EllipseShape>(0.30, 0.15, Vec2(-0.10, 0.0));
  c.object.mass = 24.0;
  c.object.inertia = 0.675;
  return c;
}

void BM_ForwardDynamicsU(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const RbsfModel model(benchCell(m));
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

BENCHMARK_MAIN();
