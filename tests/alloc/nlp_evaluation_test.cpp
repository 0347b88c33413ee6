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
  // A kinodynamic plan, and a support plan with every support row (least-norm forces on
  // three sticking tips, the tube, the floor, the motion limits).
  OptimizerSettings kinodynamic;
  kinodynamic.knots = 12;
  OptimizerSettings support = kinodynamic;
  support.stated_roles = true;
  support.normal_floor = 0.08;
  support.motion_limits = true;
  support.tube_position = 0.01;
  support.tube_angle = 0.035;
  for (const auto& [plan, settings] :
       {std::pair{&test::shortPlan(), kinodynamic}, std::pair{&test::threeTipPlan(), support}}) {
    const TrajectoryProblem p(test::defaultModel(), *plan, settings);
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
}

}  // namespace
}  // namespace rbsf::trajopt
