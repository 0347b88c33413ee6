// The optimiser's NLP evaluations (Ipopt calls them every iteration, the Hessian's
// contact wrenches by nested AutoDiff) allocate nothing once the problem is built.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../unit/trajopt_support.h"
#include "malloc_counter.h"
#include "rbsf/trajopt/plan_optimizer.h"
#include "rbsf/trajopt/trajectory_problem.h"

namespace rbsf::trajopt {
namespace {

TEST(NoAllocationTrajopt, ConstraintsJacobianAndHessianEvaluateWithoutAllocating) {
  if (!rbsf::test::mallocCountingAvailable()) GTEST_SKIP() << "malloc not countable";
  OptimizerSettings settings;
  settings.knots = 12;
  const TrajectoryProblem p(test::defaultModel(), test::shortPlan(), settings);
  ASSERT_TRUE(p.ok()) << p.why();
  const Eigen::VectorXd z = p.variables().initialGuess();
  Eigen::VectorXd g(p.rows()), grad(p.size());
  std::vector<double> jac(p.nonZeros()), hess(p.hessianPattern().size());
  const std::vector<double> lambda(p.rows(), 0.5);
  // Warm-up: workspace sized on first use is allowed.
  p.constraintValues(z, g);
  p.jacobianValues(z, jac.data());
  p.hessianValues(z, 1.0, lambda.data(), hess.data());
  const std::vector<double> hess_first = hess;

  rbsf::test::MallocCounter counter;
  const double f = p.objective(z);
  p.gradient(z, grad);
  p.constraintValues(z, g);
  p.jacobianValues(z, jac.data());
  p.hessianValues(z, 1.0, lambda.data(), hess.data());
  EXPECT_EQ(counter.count(), 0);
  EXPECT_TRUE(std::isfinite(f));
  EXPECT_TRUE(g.allFinite());
  // The second evaluation repeats the first: no state carried between calls.
  EXPECT_EQ(hess, hess_first);
}

}  // namespace
}  // namespace rbsf::trajopt
