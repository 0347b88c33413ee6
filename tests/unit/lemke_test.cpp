// Lemke's method for general LCPs: against Murty's method on P-matrices, against brute-force
// enumeration on non-symmetric ones, degenerate data, and a ray termination.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <random>
#include <stdexcept>

#include "rbsf/dynamics/core/lemke.h"
#include "rbsf/dynamics/core/small_solvers.h"

namespace rbsf {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Largest violation of z >= 0, w >= 0, z_i w_i = 0 (w = M z + q), relative to the data.
double lcpResidual(const MatrixXd& M, const VectorXd& q, const VectorXd& z) {
  const VectorXd w = M * z + q;
  const double scale = 1.0 + q.cwiseAbs().maxCoeff() + M.cwiseAbs().maxCoeff() * z.cwiseAbs().sum();
  double r = 0.0;
  for (int i = 0; i < z.size(); ++i) {
    r = std::max(r, -z[i]);
    r = std::max(r, -w[i]);
    r = std::max(r, std::min(std::abs(z[i]), std::abs(w[i])));
  }
  return r / scale;
}

/// Every solution by enumerating the 2^n complementary bases (small n only).
std::vector<VectorXd> enumerateSolutions(const MatrixXd& M, const VectorXd& q) {
  const int n = static_cast<int>(q.size());
  std::vector<VectorXd> out;
  for (int mask = 0; mask < (1 << n); ++mask) {
    std::vector<int> S;
    for (int i = 0; i < n; ++i)
      if (mask & (1 << i)) S.push_back(i);
    VectorXd z = VectorXd::Zero(n);
    if (!S.empty()) {
      MatrixXd A(S.size(), S.size());
      VectorXd b(S.size());
      for (size_t a = 0; a < S.size(); ++a) {
        b[a] = -q[S[a]];
        for (size_t c = 0; c < S.size(); ++c) A(a, c) = M(S[a], S[c]);
      }
      const Eigen::FullPivLU<MatrixXd> lu(A);
      if (!lu.isInvertible()) continue;
      const VectorXd zs = lu.solve(b);
      for (size_t a = 0; a < S.size(); ++a) z[S[a]] = zs[a];
    }
    if (lcpResidual(M, q, z) < 1e-10) out.push_back(z);
  }
  return out;
}

TEST(Lemke, AgreesWithMurtyOnSymmetricPositiveDefiniteProblems) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  LemkeWorkspace ws(kMaxFingers);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % kMaxFingers;
    MatrixXd B(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) B(i, j) = g(rng);
    const MatCC A = B * B.transpose() + 0.05 * MatrixXd::Identity(n, n);
    VecC p(n);
    for (int i = 0; i < n; ++i) p[i] = 3.0 * g(rng);
    VecC z_murty, w_murty;
    ASSERT_TRUE(solveLcp(A, p, z_murty, w_murty).solved);
    VectorXd z(n);
    const LcpStatus st = solveLcpLemke(MatrixXd(A), VectorXd(p), z, ws);
    ASSERT_TRUE(st.solved) << "trial " << trial;
    // A P-matrix LCP has exactly one solution.
    EXPECT_LT((z - VectorXd(z_murty)).cwiseAbs().maxCoeff(), 1e-9 * (1 + z.norm())) << trial;
  }
}

TEST(Lemke, SolvesNonSymmetricPMatricesUniquely) {
  // M = S + K with S positive definite and K skew: x^T M x = x^T S x > 0, a P-matrix whose
  // LCP has one solution, which brute-force enumeration finds independently.
  std::mt19937 rng(12);
  std::normal_distribution<double> g;
  LemkeWorkspace ws(8);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 2 + trial % 7;
    MatrixXd B(n, n), C(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) B(i, j) = g(rng), C(i, j) = 3.0 * g(rng);
    const MatrixXd M = B * B.transpose() + 0.1 * MatrixXd::Identity(n, n) + (C - C.transpose());
    VectorXd q(n);
    for (int i = 0; i < n; ++i) q[i] = 2.0 * g(rng);
    VectorXd z(n);
    ASSERT_TRUE(solveLcpLemke(M, q, z, ws).solved) << trial;
    const std::vector<VectorXd> all = enumerateSolutions(M, q);
    ASSERT_EQ(all.size(), 1u) << trial;
    EXPECT_LT((z - all[0]).cwiseAbs().maxCoeff(), 1e-9 * (1 + z.norm())) << trial;
  }
}

TEST(Lemke, HandlesDegenerateDataAndSingularPositiveSemidefiniteMatrices) {
  LemkeWorkspace ws(6);
  // Ties in q, zeros in q, and a rank-one PSD matrix: feasible, degenerate at every pivot.
  const VectorXd v = (VectorXd(4) << 1.0, 1.0, 1.0, 1.0).finished();
  const MatrixXd M = v * v.transpose();
  for (const VectorXd& q : {VectorXd((VectorXd(4) << -1.0, -1.0, -1.0, -1.0).finished()),
                            VectorXd((VectorXd(4) << -1.0, 0.0, -1.0, 0.0).finished()),
                            VectorXd((VectorXd(4) << 0.0, 0.0, 0.0, 0.0).finished())}) {
    VectorXd z(4);
    ASSERT_TRUE(solveLcpLemke(M, q, z, ws).solved) << q.transpose();
    EXPECT_LT(lcpResidual(M, q, z), 1e-12) << q.transpose();
  }
  // Strictly copositive (non-negative, positive diagonal) but neither symmetric nor PSD,
  // with tied q: Lemke must terminate with a solution.
  MatrixXd G(4, 4);
  G << 1, 0, 4, 2, 0, 1, 3, 5, 6, 1, 1, 0, 1, 7, 0, 1;
  VectorXd z(4);
  ASSERT_TRUE(solveLcpLemke(G, -VectorXd::Ones(4), z, ws).solved);
  EXPECT_LT(lcpResidual(G, -VectorXd::Ones(4), z), 1e-12);
}

TEST(Lemke, ReportsARayForAnInfeasibleProblem) {
  LemkeWorkspace ws(3);
  // w = -z - 1 can never be non-negative.
  const MatrixXd M = -MatrixXd::Identity(3, 3);
  VectorXd z(3);
  const LcpStatus st = solveLcpLemke(M, -VectorXd::Ones(3), z, ws);
  EXPECT_FALSE(st.solved);
  EXPECT_EQ(z, VectorXd::Zero(3));
}

TEST(Lemke, TrivialWhenQIsNonNegativeAndRejectsBadSizes) {
  LemkeWorkspace ws(2);
  VectorXd z(2);
  const LcpStatus st = solveLcpLemke(MatrixXd::Identity(2, 2), VectorXd::Ones(2), z, ws);
  EXPECT_TRUE(st.solved);
  EXPECT_EQ(st.pivots, 0);
  EXPECT_EQ(z, VectorXd::Zero(2));
  VectorXd z3(3);
  EXPECT_THROW(solveLcpLemke(MatrixXd::Identity(3, 3), VectorXd::Ones(3), z3, ws),
               std::invalid_argument);
  EXPECT_THROW(solveLcpLemke(MatrixXd::Identity(2, 2), VectorXd::Ones(2), z3, ws),
               std::invalid_argument);
}

}  // namespace
}  // namespace rbsf
