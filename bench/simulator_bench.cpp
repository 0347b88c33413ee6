// One step of the hybrid simulator with every contact touching: the part held at rest on
// m = 3 and m = 6 fingers (phase C, every contact sticking, the indeterminate case of
// paper 2.2), and the part sliding frictionlessly on m = 3 fingers (phase U).
// Also the 1 ms control loop's other two calls: sampling a reference of an optimised
// plan's size (101 knots, 100 tau ramps) and the control law.
// Part of build/bench/rbsf_micro_bench (micro_bench_main.cpp).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "rbsf/dynamics/control/contact_force_qp.h"
#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/control/reference_trajectory.h"
#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/simulator.h"

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

/// A 10 s rollout at 1 kHz (10,000 steps) of the default cell from rest under its holding
/// inputs held open loop: the base tips to its limit and the part slides (stick, slip and a
/// limit), every step's sample kept. The C++ side of the Python rollout's goal
/// (bench/python_bench.py runs the same rollout through rbsf.Simulator.rollout).
void BM_Rollout10s(benchmark::State& state) {
  const RbsfModel model(benchCell(3, 0.5));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  ModelData d(3);
  model.updateContacts(q0, d);
  const HoldingSolution hold = holdingTorques(model, q0, d);
  const VecU tau = hold.tau;
  const Simulator sim(model);
  SimulatorWorkspace ws(3);
  std::vector<TrajectorySample> samples;
  samples.reserve(10000);
  for (auto _ : state) {
    samples.clear();
    SimState s(q0, VecQ::Zero(7));
    rollout(
        sim, s, 10000, ws,
        [&](const SimState&, long, VecU& u) {
          u = tau;
          return true;
        },
        [&](const SimState& now, const StepReport& r, const VecU& u, long) {
          samples.push_back(trajectorySample(now, r, u));
          return true;
        });
    benchmark::DoNotOptimize(samples.data());
  }
  state.counters["steps"] = static_cast<double>(samples.size());
  state.counters["end_x"] = samples.back().q[layout::kX];
}
BENCHMARK(BM_Rollout10s)->Unit(benchmark::kMillisecond);

/// A reference the size of an optimised plan: 101 knots and 100 tau ramps over 2 s.
ReferenceTrajectory benchReference(const VecQ& q0) {
  ReferenceTrajectory ref;
  const int n = static_cast<int>(q0.size()), nu = n - 3;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.02 * k;
    ref.addKnot(t, q0 + VecQ::Constant(n, 0.01 * std::sin(3 * t)),
                VecQ::Constant(n, 0.03 * std::cos(3 * t)));
    if (k < 100)
      ref.addInputPiece(t, 0.02, VecU::Constant(nu, 10.0 * k), VecU::Constant(nu, 10.0 * k + 5),
                        Phase::kU);
  }
  return ref;
}

void BM_ReferenceSample(benchmark::State& state) {
  const RbsfModel model(benchCell(3, 0.5));
  const ReferenceTrajectory ref =
      benchReference(restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0));
  ReferenceSample sample;
  double t = 0.0;
  for (auto _ : state) {
    t = t >= 2.0 ? 0.0 : t + 1e-3;  // the 1 ms control loop's walk through the plan
    ref.sample(t, sample);
    benchmark::DoNotOptimize(sample.q.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ReferenceSample);

/// One control period of the control law (control_law.h) holding the part at rest on three
/// sticking fingers for 2 s (the estimator's heaviest simulator step): the step, the joint
/// update, a part pose every 10th call (carried over the 10 ms latency), and the gain;
/// Arg 1 part feedback (TV-LQR), 0 joint PD.
void BM_ControlLawCompute(benchmark::State& state) {
  const RbsfModel model(benchCell(3, 0.5));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  ModelData data(model.numFingers());
  model.updateContacts(q0, data);
  const HoldingSolution hold = holdingTorques(model, q0, data);
  ReferenceTrajectory reference;
  reference.addKnot(0.0, q0, VecQ::Zero(q0.size()));
  reference.addKnot(2.0, q0, VecQ::Zero(q0.size()));
  reference.addInputPiece(0.0, 2.0, hold.tau, VecU(), Phase::kC);
  Sensing sensing;
  sensing.part_pose.present = state.range(0) == 1;
  const FeedbackSchedule schedule(model, reference, sensing, SimulatorSettings{});
  ControlLaw law(schedule);
  ReferenceSample at;
  VecU tau, joints(model.controlDim());
  long k = 0;
  for (auto _ : state) {
    const double t = 1e-3 * static_cast<double>(k % 2000);
    if (k % 2000 == 0) law.reset();
    schedule.reference(t, at);
    for (int j = 0; j < joints.size(); ++j) joints[j] = at.q[layout::inputToConfig(j)];
    if (k % 10 == 0)
      law.addPartPose(t - 0.01, Pose{at.q[layout::kX], at.q[layout::kY], at.q[layout::kPhi]});
    law.compute(t, joints, tau);
    benchmark::DoNotOptimize(tau.data());
    benchmark::ClobberMemory();
    ++k;
  }
}
BENCHMARK(BM_ControlLawCompute)->Arg(1)->Arg(0);

/// The law's per-tick problem alone (contact_force_qp.h): prediction and QP at the default
/// part's rest, Arg 2: on two sticking tips, finger 1 lifted; 3: on three.
void BM_ContactForceQp(benchmark::State& state) {
  const RbsfModel model(benchCell(3, 0.5));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  ModelData data(model.numFingers());
  model.updateContacts(q0, data);
  const HoldingSolution hold = holdingTorques(model, q0, data);
  ContactForceQp qp(model);
  ContactTick tick;
  tick.roles = parseRoles(state.range(0) == 2 ? "LSS" : "SSS", 3, "roles");
  tick.estimated.fill(ContactMode::kSeparated);
  for (int i = 0; i < 3; ++i) tick.estimated[i] = ContactMode::kStick;
  tick.slip_floor = VecC::Zero(3);
  const VecQ v = VecQ::Zero(q0.size());
  VecU tau;
  qp.data().xi_hint = data.xi_hint;
  for (auto _ : state) {
    qp.solve(q0, v, tick, hold.tau, tau);
    benchmark::DoNotOptimize(tau.data());
  }
}
BENCHMARK(BM_ContactForceQp)->Arg(2)->Arg(3);

}  // namespace
}  // namespace rbsf
