// The velocity-level contact problem: every solution satisfies the complementarity and
// Coulomb conditions, whichever path produced it; the paths agree where the solution is
// unique; statically indeterminate sticking gets the least-norm impulses.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <random>

#include "rbsf/dynamics/core/contact_impulse_solver.h"
#include "rbsf/dynamics/core/holding.h"
#include "test_support.h"

namespace rbsf {
namespace {

struct Problem {
  int nc = 0, nl = 0;
  MatII D;
  VecI b;
  std::array<double, kMaxFingers> mu{};
};

/// Random problem: W with nc (normal, tangent) pairs and nl unit limit rows over an
/// 8-dimensional configuration, a random diagonal mass, b of mixed signs.
Problem randomProblem(std::mt19937& rng, int nc, int nl, bool frictionless) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int nq = 8, nu = nc + nl, n = nu + nc;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(nq, n);
  for (int r = 0; r < nc; ++r)
    for (int k = 0; k < nq; ++k) W(k, r) = g(rng), W(k, nu + r) = g(rng);
  for (int j = 0; j < nl; ++j) W(j % nq, nc + j) = j % 2 == 0 ? 1.0 : -1.0;
  Eigen::VectorXd minv(nq);
  for (int k = 0; k < nq; ++k) minv[k] = 0.2 + u(rng);
  Problem p;
  p.nc = nc;
  p.nl = nl;
  p.D = W.transpose() * minv.asDiagonal() * W;
  p.b.resize(n);
  for (int r = 0; r < n; ++r) p.b[r] = g(rng);
  for (int c = 0; c < nc; ++c) p.mu[c] = frictionless ? 0.0 : 1.2 * u(rng);
  return p;
}

void load(ContactImpulseSolver& s, const Problem& p, std::mt19937& rng) {
  std::bernoulli_distribution coin;
  s.resize(p.nc, p.nl);
  s.D = p.D;
  s.b = p.b;
  s.mu = p.mu;
  for (int u = 0; u < p.nc + p.nl; ++u) s.closed[u] = coin(rng);
  for (int c = 0; c < p.nc; ++c)
    s.friction[c] = static_cast<FrictionMode>(std::uniform_int_distribution<int>(0, 2)(rng));
}

/// Check the conditions of contact_impulse_solver.h on the solver's own D + eps I.
void expectSolution(const ContactImpulseSolver& s, const std::string& what) {
  const int nc = s.numContacts(), nu = s.numUnilateral();
  const VecI y = s.D * s.lambda + s.b;
  EXPECT_LT((y - s.y).cwiseAbs().maxCoeff(), 1e-9) << what;
  // The solver verifies to 1e-9 of the scale of its terms, D lambda and b.
  const double tol = 1e-8 * (1.0 + s.b.cwiseAbs().maxCoeff() +
                             s.D.cwiseAbs().maxCoeff() * s.lambda.cwiseAbs().maxCoeff());
  for (int u = 0; u < nu; ++u) {
    EXPECT_GE(s.lambda[u], -tol) << what << " row " << u;
    EXPECT_GE(y[u], -tol) << what << " row " << u;
    EXPECT_LE(std::min(s.lambda[u], y[u]), tol) << what << " row " << u;
  }
  for (int c = 0; c < nc; ++c) {
    const double lt = s.lambda[nu + c], yt = y[nu + c], bound = s.mu[c] * s.lambda[c];
    EXPECT_LE(std::abs(lt), bound + tol) << what << " contact " << c;
    if (std::abs(lt) < bound - tol) {
      EXPECT_LE(std::abs(yt), tol) << what << " contact " << c;
    }
    if (std::abs(yt) > tol) {
      EXPECT_NEAR(lt, -bound * (yt > 0 ? 1.0 : -1.0), tol) << what << " contact " << c;
    }
  }
}

TEST(ContactImpulseSolver, EverySolutionSatisfiesComplementarityAndCoulomb) {
  std::mt19937 rng(21);
  ContactImpulseSolver s;
  int lemke = 0, guess = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int nc = 1 + trial % 4, nl = trial % 3;
    const Problem p = randomProblem(rng, nc, nl, false);
    load(s, p, rng);
    const ImpulseSolvePath path = s.solve();
    ASSERT_NE(path, ImpulseSolvePath::kFailed) << trial;
    (path == ImpulseSolvePath::kLemke ? lemke : guess)++;
    expectSolution(s, "trial " + std::to_string(trial));
    // Lemke alone solves the same problem.
    load(s, p, rng);
    s.max_mode_iterations = 0;
    ASSERT_EQ(s.solve(), ImpulseSolvePath::kLemke) << trial;
    s.max_mode_iterations = 8;
    expectSolution(s, "Lemke, trial " + std::to_string(trial));
  }
  // Both paths were exercised by the mode guesses.
  EXPECT_GT(guess, 0);
  EXPECT_GT(lemke, 0);
}

TEST(ContactImpulseSolver, PathsAgreeWhenTheSolutionIsUnique) {
  // Frictionless with independent rows: D is positive definite, one solution.
  std::mt19937 rng(22);
  ContactImpulseSolver s;
  for (int trial = 0; trial < 100; ++trial) {
    const Problem p = randomProblem(rng, 1 + trial % 3, trial % 2, true);
    load(s, p, rng);
    s.solve();
    const VecI fast = s.lambda;
    load(s, p, rng);
    s.max_mode_iterations = 0;
    s.solve();
    s.max_mode_iterations = 8;
    EXPECT_LT((fast - s.lambda).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + fast.norm())) << trial;
  }
}

TEST(ContactImpulseSolver, IndeterminateStickingGetsLeastNormImpulses) {
  // A part resting on three sticking fingers: the 6 contact rows have rank 5 (paper 2.2).
  // The right-hand side is that of the held part at rest, perturbed by 1e-12 m/s off the
  // range of D (as rounding or curvature terms do). The impulses must be the least-norm
  // ones, with no component rhs_perp / eps in the squeeze.
  // mu = 1: the least-norm forces lie inside the cones, so they are the sticking forces.
  Cell cell = test::makeCell(test::ShapeKind::kEllipse, 3);
  cell.friction.mu_static = 1.0;
  const RbsfModel model(cell);
  const VecQ q = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  ModelData d(3);
  model.updateContacts(q, d);
  const HoldingSolution hold = holdingTorques(model, q, d);
  ASSERT_TRUE(hold.feasible);
  const double h = 1e-3;
  Eigen::MatrixXd W(7, 6);
  W << d.G1, d.T;
  Eigen::MatrixXd MinvW = W;
  model.applyMassInverse(q, MinvW);
  VecQ u, Q, acc;
  model.generalizedInput(VecU(hold.tau), u);
  model.bias(q, VecQ::Zero(7), Q);
  acc = u - Q;
  model.applyMassInverse(q, acc);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(W, Eigen::ComputeFullV);
  ASSERT_LT(svd.singularValues()[5], 1e-12);
  const Eigen::VectorXd squeeze = svd.matrixV().col(5);
  ContactImpulseSolver s;
  s.resize(3, 0);
  s.D = W.transpose() * MinvW;
  s.b = h * W.transpose() * acc + 1e-12 * squeeze;
  for (int c = 0; c < 3; ++c) s.mu[c] = 1.0, s.closed[c] = true;
  ASSERT_EQ(s.solve(), ImpulseSolvePath::kModeGuess);
  Eigen::VectorXd lambda(6);
  lambda << hold.fn, hold.ft;
  lambda *= h;
  // holdingTorques() returns the least-norm forces that fit the cones: the same point.
  // Without the second solve the squeeze would carry 1e-12 / eps ~ 2e-3 N s.
  EXPECT_LT(std::abs(squeeze.dot(s.lambda)), 1e-7 * lambda.norm()) << s.lambda.transpose();
  EXPECT_LT((s.lambda - lambda).cwiseAbs().maxCoeff(), 1e-6 * lambda.norm())
      << s.lambda.transpose() << "\n"
      << lambda.transpose();
}

}  // namespace
}  // namespace rbsf
