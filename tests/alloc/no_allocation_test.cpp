// Hot paths allocate nothing: operator new is counted in this binary, and one
// acceleration-level evaluation after warm-up must not call it.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "../unit/test_support.h"
#include "rbsf/dynamics/forward_dynamics.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace rbsf {
namespace {

TEST(NoAllocation, ForwardDynamicsEvaluation) {
  for (int m : {2, 3, 6, 8}) {
    const RbsfModel model(test::makeCell(test::ShapeKind::kSuperellipse, m));
    std::mt19937 rng(m);
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(model.configDim(), rng, 0.3);
    const VecU tau = test::randomVector(model.controlDim(), rng, 100.0);
    ModelData data(m);
    forwardDynamicsU(model, q, v, tau, data);  // warm-up: global closest-point search
    const long before = g_allocations.load();
    for (int k = 0; k < 100; ++k) forwardDynamicsU(model, q, v, tau, data);
    EXPECT_EQ(g_allocations.load() - before, 0) << "m = " << m;
  }
}

}  // namespace
}  // namespace rbsf
