// One cold-started SmallQp::solve() (dynamics/.../small_qp.h) on a control-law-sized QP:
//   SmallQp/6/20/6   6 variables, 20 inequality rows, 6 of them active at the solution
//   SmallQp/9/15/5   9 variables, 15 inequality rows, 5 of them active
// Each problem is built from its solution (fixed seed): H = B B^T + 0.5 I, a random x*, the
// active rows through x* with multipliers in [0.5, 1.5], the others 0.1..1 away from it, and
// g = -H x* + A_active^T lambda. The counters give the solver's steps and the active rows.
#include <benchmark/benchmark.h>

#include <random>

#include "rbsf/dynamics/core/small_qp.h"

namespace rbsf {
namespace {

void buildProblem(int n, int rows, int active, SmallQp& qp) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  qp.resize(n, 0, rows);
  QpMatNN B(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) B(i, j) = u(rng);
  }
  qp.H = B * B.transpose();
  qp.H.diagonal().array() += 0.5;
  QpVecN x_star(n);
  for (int j = 0; j < n; ++j) x_star[j] = u(rng);
  qp.g = -qp.H * x_star;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < n; ++j) qp.A(i, j) = u(rng);
    qp.b[i] = qp.A.row(i).dot(x_star);
    // The active rows are spread over the set, not its first rows.
    if (i % (rows / active) == 0 && i / (rows / active) < active) {
      qp.g += (0.5 + pos(rng)) * qp.A.row(i).transpose();
    } else {
      qp.b[i] -= 0.1 + 0.9 * pos(rng);
    }
  }
}

void BM_SmallQp(benchmark::State& state) {
  SmallQp qp;
  buildProblem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
               static_cast<int>(state.range(2)), qp);
  if (qp.solve() != QpStatus::kOptimal) state.SkipWithError("the problem is not solved");
  for (auto _ : state) {
    benchmark::DoNotOptimize(qp.solve());
    benchmark::DoNotOptimize(qp.x.data());
    benchmark::ClobberMemory();
  }
  state.counters["steps"] = qp.iterations;
  state.counters["active"] = qp.num_active;
}
BENCHMARK(BM_SmallQp)->Args({6, 20, 6})->Args({9, 15, 5});

}  // namespace
}  // namespace rbsf
