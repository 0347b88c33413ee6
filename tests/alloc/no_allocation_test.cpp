// Hot paths allocate nothing: mallocs are counted around each one after warm-up.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "../unit/test_support.h"
#include "malloc_counter.h"
#include "rbsf/dynamics/forward_dynamics.h"
#include "rbsf/dynamics/small_solvers.h"

namespace rbsf {
namespace {

class NoAllocation : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::mallocCountingAvailable()) GTEST_SKIP() << "malloc not countable in this build";
  }
};

TEST_F(NoAllocation, CounterSeesMalloc) {
  test::MallocCounter counter;
  void* volatile probe = std::malloc(64);
  std::free(probe);
  EXPECT_EQ(counter.count(), 1);
}

TEST_F(NoAllocation, LcpSolve) {
  std::mt19937 rng(5);
  std::vector<MatCC> As;
  std::vector<VecC> ps;
  for (int n = 1; n <= kMaxFingers; ++n) {
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
    As.push_back(MatCC(B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n)));
    ps.push_back(VecC(Eigen::VectorXd::Random(n)));  // mixed signs: pivoting happens
  }
  VecC z, w;
  int pivots = 0;
  test::MallocCounter counter;
  for (size_t i = 0; i < As.size(); ++i) pivots += solveLcp(As[i], ps[i], z, w).pivots;
  EXPECT_EQ(counter.count(), 0);
  EXPECT_GT(pivots, 0);
}

TEST_F(NoAllocation, ForwardDynamicsEvaluation) {
  for (int m : {2, 3, 6, 8}) {
    const RbsfModel model(test::makeCell(test::ShapeKind::kSuperellipse, m));
    std::mt19937 rng(m);
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(model.configDim(), rng, 0.3);
    const VecU tau = test::randomVector(model.controlDim(), rng, 100.0);
    ModelData data(m);
    forwardDynamicsU(model, q, v, tau, data);  // warm-up: global closest-point search
    test::MallocCounter counter;
    for (int k = 0; k < 100; ++k) forwardDynamicsU(model, q, v, tau, data);
    EXPECT_EQ(counter.count(), 0) << "m = " << m;
  }
}

}  // namespace
}  // namespace rbsf
