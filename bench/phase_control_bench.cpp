// Inverse dynamics by phase on the default cell (m = 3), as a planner's control sampler
// calls it at each new state: take the state (contacts, velocity products, the affine
// maps of both phases), then one target solve or one sample from fractions.
#include <benchmark/benchmark.h>

#include <string>

#include <Eigen/SVD>

#include "rbsf/dynamics/phase_control.h"
#include "rbsf/dynamics/placement.h"

namespace rbsf {
namespace {

struct Fixture {
  Fixture() : model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml")), data(3) {
    q = restingConfiguration(model, Pose{0.10, 0.40, 0.05}, 0.1);
    model.updateContacts(q, data);
    // Sticking velocity (base rotation and common stroke): phase C is defined here, and
    // the velocity products are not zero.
    Eigen::MatrixXd C(6, 7);
    C << data.G1.transpose(), data.T.transpose();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
    v = svd.matrixV().rightCols(2) * Eigen::Vector2d(0.3, -0.2);
  }
  RbsfModel model;
  ModelData data;
  VecQ q, v;
};

void BM_SetState(benchmark::State& state) {
  Fixture f;
  PhaseControl pc(f.model);
  for (auto _ : state) {
    f.model.updateContacts(f.q, f.data);
    pc.setState(f.q, f.v, f.data);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SetState);

// One phase C target: setState + solveC.
void BM_PhaseCTarget(benchmark::State& state) {
  Fixture f;
  PhaseControl pc(f.model);
  for (auto _ : state) {
    f.model.updateContacts(f.q, f.data);
    pc.setState(f.q, f.v, f.data);
    const PhaseControlResult r = pc.solveC(1.5, 0.3);
    if (!r.feasible) state.SkipWithError("C target infeasible");
    benchmark::DoNotOptimize(r.tau.data());
  }
}
BENCHMARK(BM_PhaseCTarget);

// One phase U target: setState + solveU (with the sticking check, the default).
void BM_PhaseUTarget(benchmark::State& state) {
  Fixture f;
  PhaseControlOptions opt;
  opt.check_sticking = state.range(0) != 0;
  PhaseControl pc(f.model, opt);
  for (auto _ : state) {
    f.model.updateContacts(f.q, f.data);
    pc.setState(f.q, f.v, f.data);
    const PhaseControlResult r = pc.solveU(-5.0);
    if (!r.feasible) state.SkipWithError("U target infeasible");
    benchmark::DoNotOptimize(r.tau.data());
  }
}
BENCHMARK(BM_PhaseUTarget)->ArgName("check_sticking")->Arg(1)->Arg(0);

// The sampler's call: setState + ranges (LPs) + solve. C: 4 LPs; U: 2 LPs, or 4 with a
// theta'' fraction.
void BM_Sample(benchmark::State& state) {
  Fixture f;
  PhaseControl pc(f.model);
  const Phase phase = state.range(0) == 0 ? Phase::kC : Phase::kU;
  const double secondary = state.range(1) != 0 ? -0.4 : PhaseControl::kFree;
  for (auto _ : state) {
    f.model.updateContacts(f.q, f.data);
    pc.setState(f.q, f.v, f.data);
    const PhaseControlResult r = pc.sample(phase, 0.3, secondary);
    if (!r.feasible) state.SkipWithError("sample infeasible");
    benchmark::DoNotOptimize(r.tau.data());
  }
}
BENCHMARK(BM_Sample)->ArgNames({"U", "secondary"})->Args({0, 1})->Args({1, 0})->Args({1, 1});

// Further samples at the same state: the first range is cached, so C costs 2 LPs and U
// (no theta'' fraction) none.
void BM_SampleAgain(benchmark::State& state) {
  Fixture f;
  PhaseControl pc(f.model);
  const Phase phase = state.range(0) == 0 ? Phase::kC : Phase::kU;
  const double secondary = state.range(1) != 0 ? -0.4 : PhaseControl::kFree;
  pc.setState(f.q, f.v, f.data);
  for (auto _ : state) {
    const PhaseControlResult r = pc.sample(phase, 0.3, secondary);
    if (!r.feasible) state.SkipWithError("sample infeasible");
    benchmark::DoNotOptimize(r.tau.data());
  }
}
BENCHMARK(BM_SampleAgain)->ArgNames({"U", "secondary"})->Args({0, 1})->Args({1, 0})->Args({1, 1});

}  // namespace
}  // namespace rbsf
