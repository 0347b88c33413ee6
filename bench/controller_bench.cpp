// The controller facade's real-time path: sample() and track() on a published plan (the
// default cell's 15 degree turn, a knot every 1 ms step), at scattered times and at 1 ms
// steps as a loop samples, alone and while a planning request runs on the worker thread;
// ReferenceTrajectory::sample() alone for the cost of publication.
// Part of build/bench/rbsf_micro_bench (micro_bench_main.cpp), e.g.
//   build/bench/rbsf_micro_bench --benchmark_filter=Controller --benchmark_repetitions=10
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/plan/plan_reference.h"

namespace rbsf::controller {
namespace {

controller::ReorientationRequest turn(double degrees, std::uint32_t seed) {
  ReorientationRequest r;
  r.problem.start = {0.1, 0.40, 0.0};
  r.problem.goal = {0.1, 0.40, degrees * M_PI / 180.0};
  r.planner.seed = seed;
  r.planner.time_limit = 120.0;
  r.certificate.trials = 4;
  r.accept_uncertified = true;  // the real-time path, not the plan, is measured
  return r;
}

/// One controller with the 15 degree plan published, shared by the benchmarks.
ReorientationController& readyController() {
  static const std::unique_ptr<ReorientationController> c = [] {
    auto p = std::make_unique<ReorientationController>(std::string(RBSF_SOURCE_DIR) +
                                                       "/cells/default.yaml");
    p->plan(turn(-15.0, 7));
    p->wait();
    if (p->status() != ControllerStatus::kReady) std::abort();
    return p;
  }();
  return *c;
}

/// Times spread over the plan (and a little beyond both ends), visited in a fixed order.
double sampleTime(long k, double duration) {
  return std::fmod(0.6180339887 * static_cast<double>(k), 1.2) * duration - 0.1 * duration;
}

void BM_ControllerSample(benchmark::State& state) {
  ReorientationController& c = readyController();
  double duration = 0.0;
  VecQ q0;
  c.publishedPlan(duration, q0);
  ReferenceSample ref;
  c.sample(0.0, ref);
  long k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.sample(sampleTime(k++, duration), ref));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ControllerSample);

/// As a 1 kHz loop samples: t advancing by 1 ms through the plan, then again from 0.
void BM_ControllerSampleSequential(benchmark::State& state) {
  ReorientationController& c = readyController();
  double duration = 0.0;
  VecQ q0;
  c.publishedPlan(duration, q0);
  ReferenceSample ref;
  c.sample(0.0, ref);
  const long period = std::lround(duration / 1e-3) + 1;
  long k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.sample(1e-3 * static_cast<double>(k++ % period), ref));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ControllerSampleSequential);

/// track() as the 1 kHz loop calls it: the published plan's control law (part feedback on
/// the default cell), t advancing by 1 ms through the plan and its hold, a part pose every
/// 10th call; the law restarts with each pass.
void BM_ControllerTrack(benchmark::State& state) {
  ReorientationController& c = readyController();
  double duration = 0.0;
  VecQ q0;
  c.publishedPlan(duration, q0);
  ReferenceSample ref;
  VecU tau, joints(c.model().controlDim());
  const long period = std::lround(duration / 1e-3) + 1;
  long k = 0;
  for (auto _ : state) {
    const double t = 1e-3 * static_cast<double>(k % period);
    c.sample(t, ref);
    for (int j = 0; j < joints.size(); ++j) joints[j] = ref.q[3 + j];
    if (k % 10 == 0) c.addPartPose(t, Pose{ref.q[0], ref.q[1], ref.q[2]});
    benchmark::DoNotOptimize(c.track(t, joints, tau));
    benchmark::ClobberMemory();
    ++k;
  }
}
BENCHMARK(BM_ControllerTrack);

/// sample() while the worker searches (a request with micrometre tolerances that never
/// finishes; cancelled at the end). On the 2-core VM the two threads share the cores with
/// whatever else runs.
void BM_ControllerSampleWhilePlanning(benchmark::State& state) {
  ReorientationController& c = readyController();
  double duration = 0.0;
  VecQ q0;
  c.publishedPlan(duration, q0);
  ReorientationRequest endless = turn(-90.0, 1);
  endless.planner.position_tolerance = 1e-6;
  endless.planner.angle_tolerance = 1e-6;
  endless.planner.time_limit = 600.0;
  if (!c.plan(endless)) std::abort();
  ReferenceSample ref;
  c.sample(0.0, ref);
  long k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.sample(sampleTime(k++, duration), ref));
    benchmark::ClobberMemory();
  }
  c.cancel();
  c.wait();
}
BENCHMARK(BM_ControllerSampleWhilePlanning);

/// The reference alone, without the facade's publication: the facade's overhead is the
/// difference to BM_ControllerSample.
void BM_ReferenceTrajectorySample(benchmark::State& state) {
  const plan::Plan plan = readyController().result().plan;
  const ReferenceTrajectory reference = plan::makeReference(plan);
  ReferenceSample ref;
  reference.sample(0.0, ref);
  long k = 0;
  const double duration = plan.duration();
  for (auto _ : state) {
    reference.sample(sampleTime(k++, duration), ref);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ReferenceTrajectorySample);

}  // namespace
}  // namespace rbsf::controller
