// rbsf_micro_bench: the hot paths in one Google Benchmark program (docs/testing.md "Speed",
// BENCHMARKS.md): dynamics evaluation (dynamics_bench.cpp), simulator step
// (simulator_bench.cpp), the sampler's inverse dynamics by phase (phase_targets_bench.cpp), one
// planner propagation (propagation_bench.cpp), one optimiser solve (optimizer_bench.cpp), one
// small dense QP solve (small_qp_bench.cpp).
//   build/bench/rbsf_micro_bench --benchmark_repetitions=10 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
