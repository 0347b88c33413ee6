// The certificate's cost when no trial ends early: 32 closed-loop trials (every core) of a
// plan holding the part at rest on the default cell's three fingers for 3 s, plus the
// law's 1 s hold after the plan, so 4 s of 1 ms steps per trial, each step a plant step,
// an estimator step and the control law. Trials that drop the part stop early, which is why
// the certificates of today's 180 degree plans cost far less (rbsf_certificate_bench).
// Part of build/bench/rbsf_micro_bench, e.g.
//   build/bench/rbsf_micro_bench --benchmark_filter=Certificate --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <string>

#include "law_support.h"
#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"

namespace rbsf {
namespace {

void BM_CertificateFullLength(benchmark::State& state) {
  const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  const plan::Plan plan = test::holdPlan(model, q0, 3.0);
  plan::CertificateSettings settings;
  settings.trials = 32;  // a fixed count: the cost of 32 trials, whatever the bound decides
  int successes = 0;
  for (auto _ : state) {
    const plan::Certificate c = plan::certify(model, plan, settings);
    successes = c.successes;
    benchmark::DoNotOptimize(successes);
  }
  state.counters["successes"] = successes;
}
BENCHMARK(BM_CertificateFullLength)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace rbsf
