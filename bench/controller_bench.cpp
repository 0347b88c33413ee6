// The controller facade's real-time path: sample() and track() on a published plan (the
// default cell's 15 degree turn, a knot every 1 ms step), at scattered times and at 1 ms
// steps as a loop samples, alone and while a planning request runs on the worker thread;
// ReferenceTrajectory::sample() alone for the cost of publication; track() on a plan given
// to load() (the support planner's certified -15 degree turn), with the run's agreement with
// the certificate's nominal trial as counters.
// Part of build/bench/rbsf_micro_bench (micro_bench_main.cpp), e.g.
//   build/bench/rbsf_micro_bench --benchmark_filter=Controller --benchmark_repetitions=10
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/plan/trial.h"
#include "rbsf/planner/support/support_planner.h"

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

/// A plan published by load(): the support planner's -15 degree turn of the default cell,
/// certified (64 trials), and its nominal trial (plan::traceTrial(-1)); then one run of the
/// facade's loop on the nominal plant with exact joints, as docs/library.md's recipe runs
/// it: its final state against the trial's and its largest input against the limits.
struct LoadedRun {
  std::unique_ptr<ReorientationController> c;
  plan::Plan plan;
  plan::Certificate certificate;        ///< of `plan`, 64 trials
  std::vector<TrajectorySample> trace;  ///< the nominal trial's states
  double state_difference = 0.0;        ///< max |q_facade - q_trial| at the end
  double goal_distance = 0.0;           ///< |(x, y) - goal| at the end [m]
  double max_input = 0.0;               ///< max over ticks and inputs of |tau_j| / limit_j
};

const LoadedRun& loadedRun() {
  static const std::unique_ptr<LoadedRun> run = [] {
    auto r = std::make_unique<LoadedRun>();
    r->c = std::make_unique<ReorientationController>(std::string(RBSF_SOURCE_DIR) +
                                                     "/cells/default.yaml");
    const RbsfModel& model = r->c->model();
    planner::SupportPlanner planner(model, planner::SupportPlannerSettings{});
    planner::Problem problem;
    problem.start = {0.1, 0.40, 0.0};
    problem.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
    if (!planner.solve(problem, r->plan)) std::abort();
    r->certificate = plan::certify(model, r->plan, plan::CertificateSettings{});
    std::string why;
    plan::PlanRecord record;
    record.plan = r->plan;
    record.certificate = r->certificate;
    if (!r->c->load(record, &why)) std::abort();
    plan::traceTrial(model, r->plan, plan::CertificateSettings{}, -1, r->trace);
    const Simulator sim(model, r->plan.simulator);
    SimulatorWorkspace ws(model.numFingers());
    SimState s(plan::nominalDraw(model.cell(), r->plan).q0, VecQ::Zero(r->plan.q0.size()));
    VecU joints(model.controlDim()), tau;
    for (std::size_t k = 0; k < r->trace.size(); ++k) {
      for (int j = 0; j < joints.size(); ++j) joints[j] = s.q[layout::inputToConfig(j)];
      r->c->track(1e-3 * static_cast<double>(k), joints, tau);
      for (int j = 0; j < tau.size(); ++j)
        r->max_input = std::max(r->max_input, std::abs(tau[j]) / model.cell().inputLimit(j));
      sim.step(s, tau, ws);
    }
    r->state_difference = (s.q - r->trace.back().q).cwiseAbs().maxCoeff();
    r->goal_distance =
        std::hypot(s.q[layout::kX] - r->plan.goal.x, s.q[layout::kY] - r->plan.goal.y);
    return r;
  }();
  return *run;
}

/// Tick k of the loaded run's loop: the joints of its nominal trial at that tick (the plan's
/// start at tick 0 of each pass) and the plan time, in ms steps.
double loadedTick(const LoadedRun& r, long k, VecU& joints) {
  const long n = k % static_cast<long>(r.trace.size());
  const VecQ& q = n == 0 ? r.plan.q0 : r.trace[static_cast<std::size_t>(n - 1)].q;
  for (int j = 0; j < joints.size(); ++j) joints[j] = q[layout::inputToConfig(j)];
  return 1e-3 * static_cast<double>(n);
}

/// track() on the loaded plan as the 1 kHz loop calls it: t advancing by 1 ms through the
/// plan and its hold, the joints those of the nominal trial at t (a reading the estimate
/// agrees with); the law restarts with each pass. Counters: the run above.
void BM_ControllerTrackLoadedPlan(benchmark::State& state) {
  const LoadedRun& r = loadedRun();
  ReorientationController& c = *r.c;
  VecU tau, joints(c.model().controlDim());
  long k = 0;
  for (auto _ : state) {
    const double t = loadedTick(r, k++, joints);
    benchmark::DoNotOptimize(c.track(t, joints, tau));
    benchmark::ClobberMemory();
  }
  state.counters["vs_trial"] = r.state_difference;
  state.counters["goal_m"] = r.goal_distance;
  state.counters["max_input"] = r.max_input;
  state.counters["certified"] = r.certificate.certified ? 1.0 : 0.0;
}
BENCHMARK(BM_ControllerTrackLoadedPlan);

/// The same ticks through track() with its status struct filled: what a loop that reads the
/// status pays (the status is measured either way; this adds its copy).
void BM_ControllerTrackLoadedPlanWithStatus(benchmark::State& state) {
  const LoadedRun& r = loadedRun();
  ReorientationController& c = *r.c;
  VecU tau, joints(c.model().controlDim());
  ExecutionStatus status;
  long k = 0;
  for (auto _ : state) {
    const double t = loadedTick(r, k++, joints);
    benchmark::DoNotOptimize(c.track(t, joints, tau, status));
    benchmark::ClobberMemory();
  }
  state.counters["leaving"] = status.verdict == ExecutionVerdict::kLeaving ? 1.0 : 0.0;
}
BENCHMARK(BM_ControllerTrackLoadedPlanWithStatus);

/// The bare control law on the same plan and ticks, without the executor's guard, status and
/// hold: track()'s cost without them (the difference is the executor's overhead).
void BM_ControlLawLoadedPlan(benchmark::State& state) {
  const LoadedRun& r = loadedRun();
  const RbsfModel& model = r.c->model();
  const FeedbackSchedule schedule(model, plan::makeReference(r.plan),
                                  plan::lawSensing(model.cell().sensing, r.plan), r.plan.simulator);
  ControlLaw law(schedule);
  VecU tau, joints(model.controlDim());
  long k = 0;
  for (auto _ : state) {
    const double t = loadedTick(r, k++, joints);
    benchmark::DoNotOptimize(law.compute(t, joints, tau));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ControlLawLoadedPlan);

/// sample() while the worker searches (a request with micrometre tolerances that never
/// finishes; cancelled at the end). On the 2-core VM the two threads share the cores with
/// whatever else runs.
void BM_ControllerSampleWhilePlanning(benchmark::State& state) {
  ReorientationController& c = readyController();
  double duration = 0.0;
  VecQ q0;
  c.publishedPlan(duration, q0);
  ReorientationRequest endless = turn(-90.0, 1);
  endless.problem.tolerance = {1e-6, 1e-6};
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
  const plan::Plan plan = readyController().result().record.plan;
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
