// One step of the hybrid simulator with every contact touching: the part held at rest on
// m = 3 and m = 6 fingers (phase C, every contact sticking, the indeterminate case of
// paper 2.2), and the part sliding frictionlessly on m = 3 fingers (phase U).
// Part of build/bench/rbsf_micro_bench (micro_bench_main.cpp).
#include <benchmark/benchmark.h>

#include <memory>

#include "rbsf/dynamics/holding.h"
#include "rbsf/dynamics/placement.h"
#include "rbsf/dynamics/simulator.h"

namespace rbsf {
namespace {

/// The default cell (cells/default.yaml) with m fingers spread over [-0.2, 0.2] m.
Cell benchCell(int m, double mu) {
  Cell c;
  c.base = {5.0, -0.785398, 0.785398, 400.0};
  for (int i = 0; i < m; ++i) {
    FingerParams f;
    f.r = -0.20 + 0.40 * i / (m - 1);
    f.stroke_min = 0.05;
    f.stroke_max = 0.55;
    f.mass = 2.0;
    f.force_limit = 800.0;
    c.fingers.push_back(f);
  }
  c.object.shape = std::make_shared<EllipseShape>(0.30, 0.15, Vec2(-0.10, 0.0));
  c.object.mass = 24.0;
  c.object.inertia = 0.675;
  c.friction = {mu, 0.0};
  return c;
}

void BM_SimulatorStepHeld(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const RbsfModel model(benchCell(m, 0.5));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  ModelData d(m);
  model.updateContacts(q0, d);
  const HoldingSolution hold = holdingTorques(model, q0, d);
  if (!hold.feasible) state.SkipWithError("no holding tau");
  const Simulator sim(model);
  SimulatorWorkspace ws(m);
  SimState s(q0, VecQ::Zero(m + 4));
  StepReport report;
  VecU tau = hold.tau;
  sim.step(s, tau, ws, &report);
  for (auto _ : state) {
    // The base angle is an inverted pendulum: a PD (zero at rest) keeps the part held.
    tau[layout::kTauTheta] =
        hold.tau[layout::kTauTheta] - 2e3 * s.q[layout::kTheta] - 300.0 * s.v[layout::kTheta];
    sim.step(s, tau, ws, &report);
    benchmark::DoNotOptimize(s.q.data());
    benchmark::ClobberMemory();
  }
  if (report.touching != m || report.phase != Phase::kC) state.SkipWithError("part not held");
}
BENCHMARK(BM_SimulatorStepHeld)->Arg(3)->Arg(6);

void BM_SimulatorStepSliding(benchmark::State& state) {
  // Frictionless, no gravity, the part pressed by constant finger forces while it slides and
  // turns (the energy test of tests/unit/simulator_test.cpp); restarted every 2000 steps.
  const int m = static_cast<int>(state.range(0));
  Cell cell = benchCell(m, 0.0);
  cell.gravity = 0.0;
  const RbsfModel model(cell);
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  ModelData d(m);
  model.updateContacts(q0, d);
  VecQ v0 = VecQ::Zero(m + 4);
  v0[layout::kX] = 0.01, v0[layout::kY] = -0.05, v0[layout::kPhi] = 0.05;
  for (int i = 0; i < m; ++i)
    v0[layout::stroke(i)] = -d.G1.col(i).dot(v0) / d.G1(layout::stroke(i), i);
  VecU tau = VecU::Constant(m + 1, 0.1);
  tau[layout::kTauTheta] = 0.0;
  const Simulator sim(model);
  SimulatorWorkspace ws(m);
  SimState s(q0, v0);
  const SimState start = s;
  StepReport report;
  int k = 0;
  for (auto _ : state) {
    if (++k == 2000) s = start, k = 0;
    sim.step(s, tau, ws, &report);
    benchmark::DoNotOptimize(s.q.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SimulatorStepSliding)->Arg(3);

}  // namespace
}  // namespace rbsf
