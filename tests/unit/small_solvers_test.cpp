// Tests of the small dense solvers against brute-force enumeration on random problems.

#include "rbsf/dynamics/core/small_solvers.h"

#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "test_support.h"

namespace rbsf {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kInf = std::numeric_limits<double>::infinity();

using test::randomMatrix;

VectorXd randomVector(std::mt19937& rng, Index n) { return randomMatrix(rng, n, 1); }

MatCC randomSpd(std::mt19937& rng, Index n) {
  const MatrixXd b = randomMatrix(rng, n, n);
  return MatCC(b * b.transpose() + 0.1 * MatrixXd::Identity(n, n));
}

// ---------------------------------------------------------------------------------------
// LCP

// All solutions over the 2^n complementary active sets.
std::vector<VectorXd> bruteForceLcp(const MatrixXd& A, const VectorXd& p) {
  const Index n = p.size();
  std::vector<VectorXd> out;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    std::vector<Index> s;
    for (Index i = 0; i < n; ++i) {
      if (mask & (1u << i)) s.push_back(i);
    }
    VectorXd z = VectorXd::Zero(n);
    if (!s.empty()) {
      const MatrixXd Ass = A(s, s);
      const VectorXd zs = Ass.fullPivLu().solve(VectorXd(-p(s)));
      z(s) = zs;
    }
    const VectorXd w = A * z + p;
    if (z.minCoeff() >= -1e-9 && w.minCoeff() >= -1e-9) out.push_back(z);
  }
  return out;
}

void expectLcpSolution(const MatCC& A, const VecC& p, const VecC& z, const VecC& w) {
  const double scale = 1.0 + p.cwiseAbs().maxCoeff();
  ASSERT_EQ(z.size(), p.size());
  ASSERT_EQ(w.size(), p.size());
  for (Index i = 0; i < p.size(); ++i) {
    EXPECT_GE(z(i), 0.0);
    EXPECT_GE(w(i), 0.0);
    EXPECT_EQ(z(i) * w(i), 0.0) << "complementarity must be exact, i = " << i;
  }
  EXPECT_LE((A * z + p - w).cwiseAbs().maxCoeff(), 1e-9 * scale);
}

TEST(SolveLcp, RandomPositiveDefiniteMatchesBruteForce) {
  int cases = 0;
  for (Index n = 1; n <= kMaxFingers; ++n) {
    const unsigned seeds = n <= 8 ? 60 : 8;  // brute force costs 2^n solves
    for (unsigned seed = 0; seed < seeds; ++seed) {
      std::mt19937 rng(1000 * static_cast<unsigned>(n) + seed);
      const MatCC A = randomSpd(rng, n);
      const VecC p = randomVector(rng, n);
      VecC z, w;
      const LcpStatus st = solveLcp(A, p, z, w);
      ASSERT_TRUE(st.solved) << "n=" << n << " seed=" << seed;
      expectLcpSolution(A, p, z, w);
      const auto all = bruteForceLcp(A, p);
      ASSERT_EQ(all.size(), 1u) << "a P-matrix LCP has exactly one solution";
      EXPECT_LE((z - all[0]).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + all[0].norm()))
          << "n=" << n << " seed=" << seed;
      ++cases;
    }
  }
  EXPECT_EQ(cases, 8 * 60 + 4 * 8);
}

TEST(SolveLcp, NonsymmetricPMatrixMatchesBruteForce) {
  // A = SPD + skew is positive definite in the nonsymmetric sense, hence a P-matrix.
  for (unsigned seed = 0; seed < 100; ++seed) {
    std::mt19937 rng(seed + 77);
    const Index n = 1 + static_cast<Index>(seed % 6);
    const MatrixXd k = randomMatrix(rng, n, n);
    const MatCC A = randomSpd(rng, n) + MatCC(k - k.transpose());
    const VecC p = randomVector(rng, n);
    VecC z, w;
    ASSERT_TRUE(solveLcp(A, p, z, w).solved);
    expectLcpSolution(A, p, z, w);
    const auto all = bruteForceLcp(A, p);
    ASSERT_EQ(all.size(), 1u);
    EXPECT_LE((z - all[0]).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + all[0].norm()));
  }
}

TEST(SolveLcp, DegenerateComplementarityIllConditioned) {
  // Indices with z*_i = w*_i = 0 make the sign tests hinge on rounding noise; with
  // cond(A) up to 1e4 the tolerance must still prevent the pivoting from cycling.
  for (unsigned seed = 0; seed < 200; ++seed) {
    std::mt19937 rng(seed + 4711);
    const Index n = 2 + static_cast<Index>(seed % (kMaxFingers - 1));
    const MatrixXd q = MatrixXd(randomMatrix(rng, n, n).householderQr().householderQ());
    VectorXd eig(n);
    for (Index i = 0; i < n; ++i) eig(i) = std::pow(1e4, static_cast<double>(i) / (n - 1));
    const MatCC A = q * eig.asDiagonal() * q.transpose();
    VecC zs = VecC::Zero(n), ws = VecC::Zero(n);
    for (Index i = 0; i < n; ++i) {
      const double v = std::abs(randomVector(rng, 1)(0)) + 0.1;
      switch ((seed + static_cast<unsigned>(i)) % 3) {
        case 0:
          zs(i) = v;
          break;
        case 1:
          ws(i) = v;
          break;
        default:
          break;  // both zero
      }
    }
    const VecC p = ws - A * zs;
    VecC z, w;
    const LcpStatus st = solveLcp(A, p, z, w);
    ASSERT_TRUE(st.solved) << "seed=" << seed << " pivots=" << st.pivots;
    expectLcpSolution(A, p, z, w);
    EXPECT_LE((z - zs).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + zs.norm())) << "seed=" << seed;
  }
}

TEST(SolveLcp, AllContactsActiveNeedsNoPivot) {
  for (unsigned seed = 0; seed < 50; ++seed) {
    std::mt19937 rng(seed);
    const Index n = 1 + static_cast<Index>(seed % kMaxFingers);
    const MatCC A = randomSpd(rng, n);
    const VecC zStar = (randomVector(rng, n).array() + 1.5).matrix();  // all > 0
    const VecC p = -A * zStar;
    VecC z, w;
    const LcpStatus st = solveLcp(A, p, z, w);
    ASSERT_TRUE(st.solved);
    EXPECT_EQ(st.pivots, 0);
    EXPECT_LE((z - zStar).cwiseAbs().maxCoeff(), 1e-9 * zStar.norm());
    EXPECT_TRUE((w.array() == 0.0).all());
  }
}

TEST(SolveLcp, AllSeparatingGivesZeroForce) {
  std::mt19937 rng(5);
  const Index n = 6;
  const MatCC A = MatCC::Identity(n, n) * 2.0;
  const VecC p = (randomVector(rng, n).array() + 2.0).matrix();
  VecC z, w;
  const LcpStatus st = solveLcp(A, p, z, w);
  ASSERT_TRUE(st.solved);
  EXPECT_EQ(st.pivots, n);  // every contact opens, in index order
  EXPECT_TRUE((z.array() == 0.0).all());
  EXPECT_EQ(w, p);
}

TEST(SolveLcp, EmptyProblem) {
  MatCC A(0, 0);
  VecC p(0), z(3), w(3);
  const LcpStatus st = solveLcp(A, p, z, w);
  EXPECT_TRUE(st.solved);
  EXPECT_EQ(st.pivots, 0);
  EXPECT_EQ(z.size(), 0);
  EXPECT_EQ(w.size(), 0);
}

TEST(SolveLcp, RedundantContactsPositiveSemidefinite) {
  // Two identical contacts: A = g g^T is singular but the LCP is solvable.
  MatCC A(3, 3);
  A << 1, 1, 0.5,  //
      1, 1, 0.5,   //
      0.5, 0.5, 2;
  VecC p(3);
  p << -1, -1, 0.3;
  VecC z, w;
  ASSERT_TRUE(solveLcp(A, p, z, w).solved);
  expectLcpSolution(A, p, z, w);
  EXPECT_NEAR(z(0) + z(1), 1.0, 1e-12);
}

TEST(SolveLcp, NotAPMatrixHitsPivotLimit) {
  // w = -z - 1 can never be >= 0: no solution, the pivoting alternates until the limit.
  MatCC A(1, 1);
  A << -1;
  VecC p(1);
  p << -1;
  VecC z, w;
  const LcpStatus st = solveLcp(A, p, z, w);
  EXPECT_FALSE(st.solved);
  EXPECT_GE(st.pivots, 2);
}

// solveLcp allocates nothing: tests/alloc/no_allocation_test.cpp.

// ---------------------------------------------------------------------------------------
// NNLS

struct NnlsReference {
  double residual = std::numeric_limits<double>::infinity();
  VectorXd x;
};

// Some optimal solution has linearly independent support (Caratheodory), and on its
// support it is the unconstrained least-squares solution: enumerate supports.
NnlsReference bruteForceNnls(const MatrixXd& E, const VectorXd& f) {
  const Index n = E.cols();
  NnlsReference best;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    std::vector<Index> s;
    for (Index j = 0; j < n; ++j) {
      if (mask & (1u << j)) s.push_back(j);
    }
    VectorXd x = VectorXd::Zero(n);
    if (!s.empty()) {
      const MatrixXd Es = E(Eigen::all, s);
      const VectorXd xs = Es.completeOrthogonalDecomposition().solve(f);
      x(s) = xs;
    }
    if (x.minCoeff() < -1e-12) continue;
    const double r = (E * x - f).norm();
    if (r < best.residual) {
      best.residual = r;
      best.x = x;
    }
  }
  return best;
}

TEST(SolveNnls, RandomMatchesBruteForceAndKkt) {
  int withActive = 0;
  for (unsigned seed = 0; seed < 400; ++seed) {
    std::mt19937 rng(seed + 12345);
    const Index n = 1 + static_cast<Index>(seed % 7);
    const Index m = 1 + static_cast<Index>((seed / 7) % 9);
    const MatrixXd E = randomMatrix(rng, m, n);
    const VectorXd f = randomVector(rng, m) * 3.0;
    VectorXd x;
    ASSERT_TRUE(solveNnls(E, f, x)) << "seed=" << seed;
    ASSERT_EQ(x.size(), n);
    EXPECT_GE(x.minCoeff(), 0.0);
    const NnlsReference ref = bruteForceNnls(E, f);
    const double r = (E * x - f).norm();
    EXPECT_NEAR(r, ref.residual, 1e-9 * (1.0 + f.norm())) << "seed=" << seed;
    if (m >= n) {  // full column rank: unique minimiser
      EXPECT_LE((x - ref.x).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + ref.x.norm())) << "seed=" << seed;
    }
    // KKT: gradient E^T (E x - f) >= 0 where x = 0 and == 0 where x > 0.
    const VectorXd g = E.transpose() * (E * x - f);
    const double tol = 1e-9 * (1.0 + f.norm());
    for (Index j = 0; j < n; ++j) {
      if (x(j) > 0.0) {
        EXPECT_NEAR(g(j), 0.0, tol) << "seed=" << seed << " j=" << j;
      } else {
        EXPECT_GE(g(j), -tol) << "seed=" << seed << " j=" << j;
        ++withActive;
      }
    }
  }
  EXPECT_GT(withActive, 100);  // the bound constraints did matter
}

TEST(SolveNnls, FixedCapacityThreeRowsGivesTheSameBits) {
  // The allocation-free overload (3 rows, up to kMaxFingers columns) runs the same
  // algorithm on stack storage: its answer is the dynamic one, bit for bit.
  for (unsigned seed = 0; seed < 200; ++seed) {
    std::mt19937 rng(seed + 777);
    const Index n = 1 + static_cast<Index>(seed % kMaxFingers);
    const MatrixXd E = randomMatrix(rng, 3, n);
    const VectorXd f = randomVector(rng, 3) * 3.0;
    VectorXd x;
    ASSERT_TRUE(solveNnls(E, f, x));
    const Mat3C Es = E;
    const Eigen::Vector3d fs = f;
    VecC xs;
    ASSERT_TRUE(solveNnls(Es, fs, xs));
    ASSERT_EQ(xs.size(), n);
    for (Index j = 0; j < n; ++j) EXPECT_EQ(xs(j), x(j)) << "seed=" << seed << " j=" << j;
  }
}

TEST(SolveNnls, EdgeCases) {
  VectorXd x;
  // f = 0: x = 0.
  EXPECT_TRUE(solveNnls(MatrixXd::Identity(3, 3), VectorXd::Zero(3), x));
  EXPECT_EQ(x, VectorXd::Zero(3));
  // No columns / no rows.
  EXPECT_TRUE(solveNnls(MatrixXd(4, 0), VectorXd::Ones(4), x));
  EXPECT_EQ(x.size(), 0);
  EXPECT_TRUE(solveNnls(MatrixXd(0, 2), VectorXd(0), x));
  EXPECT_EQ(x, VectorXd::Zero(2));
  // Unconstrained optimum already nonnegative.
  MatrixXd E(3, 2);
  E << 1, 0, 0, 1, 1, 1;
  const VectorXd xs = (VectorXd(2) << 0.5, 2.0).finished();
  EXPECT_TRUE(solveNnls(E, E * xs, x));
  EXPECT_LE((x - xs).norm(), 1e-12);
  // Small but genuine components must not be mistaken for rounding noise, at any scale.
  for (double s : {1e-8, 1.0, 1e8}) {
    const VectorXd f = Eigen::Vector3d(1.0, 1e-7, -1.0) * s;
    EXPECT_TRUE(solveNnls(MatrixXd::Identity(3, 3) * s, f, x));
    EXPECT_LE((x - Eigen::Vector3d(1.0, 1e-7, 0.0)).norm(), 1e-14);
  }
  // Duplicate columns (rank deficient).
  MatrixXd D(2, 3);
  D << 1, 1, 0, 1, 1, 1;
  EXPECT_TRUE(solveNnls(D, (VectorXd(2) << 2, 3).finished(), x));
  EXPECT_NEAR((D * x - (VectorXd(2) << 2, 3).finished()).norm(), 0.0, 1e-12);
  EXPECT_GE(x.minCoeff(), 0.0);
}

// ---------------------------------------------------------------------------------------
// Least-norm point of a polyhedron

// Least-norm solution of A x = b, or nothing if inconsistent.
bool leastNormEq(const MatrixXd& A, const VectorXd& b, Index n, VectorXd& x) {
  if (A.rows() == 0) {
    x = VectorXd::Zero(n);
    return true;
  }
  x = A.completeOrthogonalDecomposition().solve(b);
  return (A * x - b).norm() <= 1e-9 * (1.0 + b.norm());
}

// The optimum x* solves [A_eq; G_S] x = [b_eq; h_S] with x* in that system's row space
// (KKT), so it is that system's least-norm solution for its active set S. Enumerate S,
// keep feasible candidates, take the smallest norm.
bool bruteForceLeastNorm(const MatrixXd& Aeq, const VectorXd& beq, const MatrixXd& G,
                         const VectorXd& h, Index n, VectorXd& best) {
  bool found = false;
  for (unsigned mask = 0; mask < (1u << G.rows()); ++mask) {
    std::vector<Index> s;
    for (Index i = 0; i < G.rows(); ++i) {
      if (mask & (1u << i)) s.push_back(i);
    }
    MatrixXd A(Aeq.rows() + static_cast<Index>(s.size()), n);
    VectorXd b(A.rows());
    A.topRows(Aeq.rows()) = Aeq;
    b.head(Aeq.rows()) = beq;
    for (std::size_t k = 0; k < s.size(); ++k) {
      A.row(Aeq.rows() + static_cast<Index>(k)) = G.row(s[k]);
      b(Aeq.rows() + static_cast<Index>(k)) = h(s[k]);
    }
    VectorXd x;
    if (!leastNormEq(A, b, n, x)) continue;
    if (G.rows() > 0 && (G * x - h).minCoeff() < -1e-9) continue;
    if (!found || x.norm() < best.norm()) best = x;
    found = true;
  }
  return found;
}

TEST(LeastNormInPolyhedron, RandomMatchesBruteForce) {
  int feasible = 0, infeasible = 0, moved = 0;
  for (unsigned seed = 0; seed < 600; ++seed) {
    std::mt19937 rng(seed + 999);
    const Index n = 1 + static_cast<Index>(seed % 4);
    const Index r = static_cast<Index>((seed / 4) % 3) % n;  // 0 .. n-1 equalities
    const Index p = static_cast<Index>((seed / 12) % 6);
    const MatrixXd Aeq = randomMatrix(rng, r, n);
    const VectorXd beq = randomVector(rng, r);
    const MatrixXd G = randomMatrix(rng, p, n);
    const VectorXd h = randomVector(rng, p);
    VectorXd ref;
    const bool refOk = bruteForceLeastNorm(Aeq, beq, G, h, n, ref);
    VectorXd x;
    const SolveStatus st = leastNormInPolyhedron(Aeq, beq, G, h, x);
    if (!refOk) {
      EXPECT_EQ(st, SolveStatus::kInfeasible) << "seed=" << seed;
      ++infeasible;
      continue;
    }
    ASSERT_EQ(st, SolveStatus::kOptimal) << "seed=" << seed;
    ++feasible;
    ASSERT_EQ(x.size(), n);
    EXPECT_LE((x - ref).norm(), 1e-8 * (1.0 + ref.norm())) << "seed=" << seed;
    if (r > 0) {
      EXPECT_LE((Aeq * x - beq).norm(), 1e-10);
    }
    if (p > 0) {
      EXPECT_GE((G * x - h).minCoeff(), -1e-10);
    }
    VectorXd x0;
    leastNormEq(Aeq, beq, n, x0);
    if ((x - x0).norm() > 1e-6) ++moved;
  }
  EXPECT_GT(feasible, 300);
  EXPECT_GT(infeasible, 10);
  EXPECT_GT(moved, 100);  // the inequalities were binding in many cases
}

TEST(LeastNormInPolyhedron, InfeasibleInequalities) {
  MatrixXd G(2, 2);
  G << 1, 0, -1, 0;  // x1 >= 1 and x1 <= 0
  VectorXd x;
  EXPECT_EQ(leastNormInPolyhedron(MatrixXd(0, 2), VectorXd(0), G, Eigen::Vector2d(1, 0), x),
            SolveStatus::kInfeasible);
  // Infeasible only together with the equality x1 + x2 = 0: x1 >= 1, x2 >= 1.
  MatrixXd Aeq(1, 2);
  Aeq << 1, 1;
  EXPECT_EQ(
      leastNormInPolyhedron(Aeq, VectorXd::Zero(1), MatrixXd::Identity(2, 2), VectorXd::Ones(2), x),
      SolveStatus::kInfeasible);
}

TEST(LeastNormInPolyhedron, DependentEqualityRows) {
  MatrixXd Aeq(3, 3);
  Aeq << 1, 1, 0,  //
      0, 1, 1,     //
      1, 2, 1;     // row 0 + row 1
  VectorXd beq(3);
  beq << 1, 2, 3;
  VectorXd x;
  ASSERT_EQ(leastNormInPolyhedron(Aeq, beq, MatrixXd(0, 3), VectorXd(0), x), SolveStatus::kOptimal);
  EXPECT_LE((Aeq * x - beq).norm(), 1e-12);
  const VectorXd ref = Aeq.topRows(2).completeOrthogonalDecomposition().solve(beq.head(2));
  EXPECT_LE((x - ref).norm(), 1e-12);
  // With an inequality that binds: x3 <= 0.
  MatrixXd G(1, 3);
  G << 0, 0, -1;
  ASSERT_EQ(leastNormInPolyhedron(Aeq, beq, G, VectorXd::Zero(1), x), SolveStatus::kOptimal);
  EXPECT_LE((x - Eigen::Vector3d(-1, 2, 0)).norm(), 1e-12);  // x3 = 0 fixes x2 = 2, x1 = -1

  beq(2) = 3.5;  // inconsistent
  EXPECT_EQ(leastNormInPolyhedron(Aeq, beq, MatrixXd(0, 3), VectorXd(0), x),
            SolveStatus::kInfeasible);
}

TEST(LeastNormInPolyhedron, TrivialNullSpace) {
  const MatrixXd Aeq = MatrixXd::Identity(2, 2);
  const VectorXd beq = Eigen::Vector2d(1, 2);
  MatrixXd G(1, 2);
  G << 1, 1;
  VectorXd x;
  EXPECT_EQ(leastNormInPolyhedron(Aeq, beq, G, VectorXd::Constant(1, 3.0), x),
            SolveStatus::kOptimal);
  EXPECT_LE((x - beq).norm(), 1e-14);
  EXPECT_EQ(leastNormInPolyhedron(Aeq, beq, G, VectorXd::Constant(1, 3.5), x),
            SolveStatus::kInfeasible);
}

TEST(LeastNormInPolyhedron, NoConstraintsAndScaleInvariance) {
  VectorXd x;
  EXPECT_EQ(leastNormInPolyhedron(MatrixXd(0, 3), VectorXd(0), MatrixXd(0, 3), VectorXd(0), x),
            SolveStatus::kOptimal);
  EXPECT_EQ(x, VectorXd::Zero(3));

  // A wedge whose apex is far from the origin compared with its tip width.
  MatrixXd G(2, 2);
  G << 1, 1e-3, -1, 1e-3;  // 1e-3 x2 >= s + |x1|: optimum (0, 1e3 s)
  for (double s : {1e-8, 1.0, 1e8}) {
    const VectorXd h = Eigen::Vector2d(1.0, 1.0) * s;
    ASSERT_EQ(leastNormInPolyhedron(MatrixXd(0, 2), VectorXd(0), G, h, x), SolveStatus::kOptimal);
    EXPECT_NEAR(x(0), 0.0, 1e-9 * s);
    EXPECT_NEAR(x(1), 1e3 * s, 1e-9 * s);
  }
}

TEST(LeastNormInPolyhedron, LargerProblemsSatisfyKkt) {
  // Too big to enumerate: check the KKT conditions instead. x is optimal iff it is feasible
  // and x = A_eq^T lambda + G_S^T mu with mu >= 0 on the active rows S; projecting onto
  // the null space Z of A_eq removes lambda, leaving an NNLS problem with zero residual.
  int binding = 0;
  for (unsigned seed = 0; seed < 200; ++seed) {
    std::mt19937 rng(seed + 2024);
    const Index n = 6 + static_cast<Index>(seed % 7);
    const Index r = static_cast<Index>(seed % 4);
    const Index p = 5 + static_cast<Index>(seed % 16);
    const MatrixXd Aeq = randomMatrix(rng, r, n);
    const MatrixXd G = randomMatrix(rng, p, n);
    // Feasible by construction: x_f satisfies everything, with random slack.
    const VectorXd xf = randomVector(rng, n) * 3.0;
    const VectorXd beq = Aeq * xf;
    const VectorXd h = G * xf - randomVector(rng, p).cwiseAbs();
    VectorXd x;
    ASSERT_EQ(leastNormInPolyhedron(Aeq, beq, G, h, x), SolveStatus::kOptimal) << seed;
    if (r > 0) {
      EXPECT_LE((Aeq * x - beq).norm(), 1e-10);
    }
    const VectorXd slack = G * x - h;
    EXPECT_GE(slack.minCoeff(), -1e-10) << seed;
    std::vector<Index> active;
    for (Index i = 0; i < p; ++i) {
      if (slack(i) <= 1e-9) active.push_back(i);
    }
    binding += active.empty() ? 0 : 1;
    const MatrixXd Z =
        r > 0 ? MatrixXd(
                    Eigen::JacobiSVD<MatrixXd>(Aeq, Eigen::ComputeFullV).matrixV().rightCols(n - r))
              : MatrixXd::Identity(n, n);
    const MatrixXd Ga = G(active, Eigen::all);
    VectorXd mu;
    ASSERT_TRUE(solveNnls(Z.transpose() * Ga.transpose(), Z.transpose() * x, mu));
    EXPECT_LE((Z.transpose() * (Ga.transpose() * mu - x)).norm(), 1e-8 * (1.0 + x.norm()))
        << "seed=" << seed;
  }
  EXPECT_GT(binding, 150);
}

// ---------------------------------------------------------------------------------------
// Linear programming

struct LpProblem {
  VectorXd c;
  MatrixXd Aeq;
  VectorXd beq;
  MatrixXd G;
  VectorXd h;
  VectorXd lower, upper;
};

// Enumerates the vertices of {A_eq x = b_eq, G x >= h, finite bounds}: every choice of
// n - rank(A_eq) inequality rows that, with the equalities, pins x down.
bool bruteForceLp(const LpProblem& lp, double& best) {
  const Index n = lp.c.size();
  MatrixXd rows(0, n);
  VectorXd rhs(0);
  auto add = [&](const VectorXd& a, double b) {
    rows.conservativeResize(rows.rows() + 1, n);
    rhs.conservativeResize(rhs.size() + 1);
    rows.row(rows.rows() - 1) = a.transpose();
    rhs(rhs.size() - 1) = b;
  };
  for (Index i = 0; i < lp.G.rows(); ++i) add(lp.G.row(i).transpose(), lp.h(i));
  for (Index j = 0; j < n; ++j) {
    const VectorXd e = VectorXd::Unit(n, j);
    if (std::isfinite(lp.lower(j))) add(e, lp.lower(j));
    if (std::isfinite(lp.upper(j))) add(-e, -lp.upper(j));
  }
  const Index k = rows.rows();
  const int need = static_cast<int>(n - lp.Aeq.rows());  // A_eq has full row rank here
  bool found = false;
  for (unsigned mask = 0; mask < (1u << k); ++mask) {
    if (std::popcount(mask) != need) continue;
    std::vector<Index> s;
    for (Index i = 0; i < k; ++i) {
      if (mask & (1u << i)) s.push_back(i);
    }
    MatrixXd A(lp.Aeq.rows() + static_cast<Index>(s.size()), n);
    VectorXd b(A.rows());
    A.topRows(lp.Aeq.rows()) = lp.Aeq;
    b.head(lp.Aeq.rows()) = lp.beq;
    for (std::size_t t = 0; t < s.size(); ++t) {
      A.row(lp.Aeq.rows() + static_cast<Index>(t)) = rows.row(s[t]);
      b(lp.Aeq.rows() + static_cast<Index>(t)) = rhs(s[t]);
    }
    Eigen::FullPivLU<MatrixXd> lu(A);
    lu.setThreshold(1e-10);
    if (lu.rank() != n) continue;
    const VectorXd x = lu.solve(b);
    if ((A * x - b).norm() > 1e-9) continue;
    if (k > 0 && (rows * x - rhs).minCoeff() < -1e-9) continue;
    const double v = lp.c.dot(x);
    if (!found || v < best) best = v;
    found = true;
  }
  return found;
}

void expectLpFeasible(const LpProblem& lp, const VectorXd& x) {
  ASSERT_EQ(x.size(), lp.c.size());
  if (lp.Aeq.rows() > 0) {
    EXPECT_LE((lp.Aeq * x - lp.beq).cwiseAbs().maxCoeff(), 1e-8);
  }
  if (lp.G.rows() > 0) {
    EXPECT_GE((lp.G * x - lp.h).minCoeff(), -1e-8);
  }
  EXPECT_GE((x - lp.lower).minCoeff(), -1e-8);
  EXPECT_GE((lp.upper - x).minCoeff(), -1e-8);
}

SolveStatus runLp(const LpProblem& lp, VectorXd& x, double& obj) {
  return solveLp(lp.c, lp.Aeq, lp.beq, lp.G, lp.h, lp.lower, lp.upper, x, &obj);
}

LpProblem randomBoundedLp(std::mt19937& rng, Index n, Index me, Index mg) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  LpProblem lp;
  lp.c = randomVector(rng, n);
  lp.Aeq = randomMatrix(rng, me, n);
  lp.beq = randomVector(rng, me) * 0.5;
  lp.G = randomMatrix(rng, mg, n);
  lp.h = randomVector(rng, mg);
  lp.lower = -1.0 - 2.0 * randomVector(rng, n).cwiseAbs().array();
  lp.upper = 1.0 + 2.0 * randomVector(rng, n).cwiseAbs().array();
  for (Index j = 0; j < n; ++j) {
    if (u(rng) < 0.25) lp.lower(j) = 0.0;
  }
  return lp;
}

void checkAgainstBruteForce(const LpProblem& lp, const char* what, unsigned seed, int& feasible,
                            int& infeasible) {
  double ref = 0.0;
  const bool refOk = bruteForceLp(lp, ref);
  VectorXd x;
  double obj = 0.0;
  const SolveStatus st = runLp(lp, x, obj);
  if (!refOk) {
    EXPECT_EQ(st, SolveStatus::kInfeasible) << what << " seed=" << seed;
    ++infeasible;
    return;
  }
  ASSERT_EQ(st, SolveStatus::kOptimal) << what << " seed=" << seed;
  ++feasible;
  expectLpFeasible(lp, x);
  EXPECT_NEAR(obj, ref, 1e-8 * (1.0 + std::abs(ref))) << what << " seed=" << seed;
  EXPECT_NEAR(obj, lp.c.dot(x), 1e-12);
}

TEST(SolveLp, RandomBoundedMatchesVertexEnumeration) {
  int feasible = 0, infeasible = 0;
  for (unsigned seed = 0; seed < 500; ++seed) {
    std::mt19937 rng(seed + 4242);
    const Index n = 2 + static_cast<Index>(seed % 3);
    const Index me = static_cast<Index>((seed / 3) % 2);
    const Index mg = static_cast<Index>((seed / 6) % 4);
    const LpProblem lp = randomBoundedLp(rng, n, me, mg);
    checkAgainstBruteForce(lp, "bounded", seed, feasible, infeasible);
  }
  EXPECT_GT(feasible, 300);
  EXPECT_GT(infeasible, 10);
}

TEST(SolveLp, FreeAndHalfBoundedVariables) {
  // The box is expressed through G rows, so the variables themselves are free, bounded
  // only above or only below: exercises the split x = x+ - x- and the reflection.
  int feasible = 0, infeasible = 0;
  for (unsigned seed = 0; seed < 300; ++seed) {
    std::mt19937 rng(seed + 31337);
    const Index n = 2 + static_cast<Index>(seed % 3);
    LpProblem lp = randomBoundedLp(rng, n, static_cast<Index>(seed % 2), 2);
    const Index mg = lp.G.rows();
    lp.G.conservativeResize(mg + 2 * n, n);
    lp.h.conservativeResize(mg + 2 * n);
    for (Index j = 0; j < n; ++j) {
      lp.G.row(mg + 2 * j) = VectorXd::Unit(n, j).transpose();
      lp.h(mg + 2 * j) = lp.lower(j);
      lp.G.row(mg + 2 * j + 1) = -VectorXd::Unit(n, j).transpose();
      lp.h(mg + 2 * j + 1) = -lp.upper(j);
      switch ((seed + static_cast<unsigned>(j)) % 3) {
        case 0:
          lp.lower(j) = -kInf;
          lp.upper(j) = kInf;
          break;
        case 1:
          lp.lower(j) = -kInf;
          break;
        default:
          lp.upper(j) = kInf;
      }
    }
    checkAgainstBruteForce(lp, "free", seed, feasible, infeasible);
  }
  EXPECT_GT(feasible, 150);
}

TEST(SolveLp, DegenerateVerticesMatchVertexEnumeration) {
  // Many constraints through one point make degenerate pivots the rule.
  int feasible = 0, infeasible = 0;
  for (unsigned seed = 0; seed < 300; ++seed) {
    std::mt19937 rng(seed + 777);
    const Index n = 2 + static_cast<Index>(seed % 3);
    LpProblem lp = randomBoundedLp(rng, n, 0, 5);
    const VectorXd apex = randomVector(rng, n) * 0.5;
    lp.h = lp.G * apex;  // all five rows pass through apex
    lp.lower = lp.lower.cwiseMin(apex);
    if (seed % 2 == 0) lp.lower.head(1) = apex.head(1);  // and a bound too
    checkAgainstBruteForce(lp, "degenerate", seed, feasible, infeasible);
  }
  EXPECT_EQ(infeasible, 0);
}

TEST(SolveLp, BealeCyclingExample) {
  // Beale (1955): cycles under Dantzig's largest-coefficient rule; optimum -5/4 at
  // x = (1, 0, 1, 0).
  LpProblem lp;
  lp.c = Eigen::Vector4d(-0.75, 20, -0.5, 6);
  lp.Aeq = MatrixXd(0, 4);
  lp.beq = VectorXd(0);
  lp.G.resize(3, 4);
  lp.G << -0.25, 8, 1, -9,  //
      -0.5, 12, 0.5, -3,    //
      0, 0, -1, 0;
  lp.h = Eigen::Vector3d(0, 0, -1);
  lp.lower = VectorXd::Zero(4);
  lp.upper = VectorXd::Constant(4, kInf);
  VectorXd x;
  double obj = 0.0;
  ASSERT_EQ(runLp(lp, x, obj), SolveStatus::kOptimal);
  EXPECT_NEAR(obj, -1.25, 1e-12);
  EXPECT_LE((x - Eigen::Vector4d(1, 0, 1, 0)).norm(), 1e-12);
}

TEST(SolveLp, InfeasibleAndUnbounded) {
  VectorXd x;
  double obj = 0.0;
  // x1 + x2 >= 3 in the unit box.
  {
    LpProblem lp;
    lp.c = Eigen::Vector2d(1, 1);
    lp.G = (MatrixXd(1, 2) << 1, 1).finished();
    lp.h = VectorXd::Constant(1, 3.0);
    lp.lower = VectorXd::Zero(2);
    lp.upper = VectorXd::Ones(2);
    EXPECT_EQ(runLp(lp, x, obj), SolveStatus::kInfeasible);
    lp.h(0) = 2.0;  // now just feasible, at the corner
    ASSERT_EQ(runLp(lp, x, obj), SolveStatus::kOptimal);
    EXPECT_NEAR(obj, 2.0, 1e-12);
  }
  // Inconsistent equalities.
  {
    LpProblem lp;
    lp.c = Eigen::Vector2d(1, 0);
    lp.Aeq = (MatrixXd(2, 2) << 1, 1, 1, 1).finished();
    lp.beq = Eigen::Vector2d(1, 2);
    lp.lower = VectorXd::Constant(2, -kInf);
    lp.upper = VectorXd::Constant(2, kInf);
    EXPECT_EQ(runLp(lp, x, obj), SolveStatus::kInfeasible);
  }
  // Crossed bounds.
  {
    LpProblem lp;
    lp.c = VectorXd::Ones(1);
    lp.lower = VectorXd::Constant(1, 2.0);
    lp.upper = VectorXd::Constant(1, 1.0);
    EXPECT_EQ(runLp(lp, x, obj), SolveStatus::kInfeasible);
  }
  // min -x1 - x2, x >= 0, x1 - x2 >= -1: the ray (1, 1) is unbounded.
  {
    LpProblem lp;
    lp.c = Eigen::Vector2d(-1, -1);
    lp.G = (MatrixXd(1, 2) << 1, -1).finished();
    lp.h = VectorXd::Constant(1, -1.0);
    lp.lower = VectorXd::Zero(2);
    lp.upper = VectorXd::Constant(2, kInf);
    EXPECT_EQ(runLp(lp, x, obj), SolveStatus::kUnbounded);
    lp.c = Eigen::Vector2d(1, 1);  // bounded the other way
    ASSERT_EQ(runLp(lp, x, obj), SolveStatus::kOptimal);
    EXPECT_NEAR(obj, 0.0, 1e-12);
  }
  // A free variable with no constraints.
  {
    LpProblem lp;
    lp.c = Eigen::Vector2d(0, 1);
    lp.lower = Eigen::Vector2d(0, -kInf);
    lp.upper = Eigen::Vector2d(1, kInf);
    EXPECT_EQ(runLp(lp, x, obj), SolveStatus::kUnbounded);
  }
  // Only an upper bound, minimising its negation: bounded; maximising it is not.
  {
    LpProblem lp;
    lp.c = VectorXd::Constant(1, -1.0);
    lp.lower = VectorXd::Constant(1, -kInf);
    lp.upper = VectorXd::Constant(1, 4.0);
    ASSERT_EQ(runLp(lp, x, obj), SolveStatus::kOptimal);
    EXPECT_NEAR(x(0), 4.0, 1e-12);
    lp.c(0) = 1.0;
    EXPECT_EQ(runLp(lp, x, obj), SolveStatus::kUnbounded);
  }
}

TEST(SolveLp, EqualityConstraintsDependentRowsAndFixedVariables) {
  LpProblem lp;
  lp.c = Eigen::Vector3d(1, 2, -1);
  lp.Aeq.resize(3, 3);
  lp.Aeq << 1, 1, 1,  //
      1, -1, 0,       //
      2, 0, 1;        // sum of the first two
  lp.beq = Eigen::Vector3d(4, 1, 5);
  lp.lower = VectorXd::Zero(3);
  lp.upper = VectorXd::Constant(3, 10.0);
  VectorXd x;
  double obj = 0.0;
  ASSERT_EQ(runLp(lp, x, obj), SolveStatus::kOptimal);
  expectLpFeasible(lp, x);
  // x2 = x1 - 1, x3 = 5 - 2 x1, x1 in [1, 2.5]: objective = 3 x1 - 2 - 5 + 2 x1 = 5 x1 - 7.
  EXPECT_NEAR(obj, -2.0, 1e-10);
  EXPECT_LE((x - Eigen::Vector3d(1, 0, 3)).norm(), 1e-10);

  lp.lower(0) = lp.upper(0) = 2.0;  // a fixed variable
  ASSERT_EQ(runLp(lp, x, obj), SolveStatus::kOptimal);
  EXPECT_NEAR(obj, 3.0, 1e-10);
  EXPECT_LE((x - Eigen::Vector3d(2, 1, 1)).norm(), 1e-10);

  EXPECT_EQ(solveLp(lp.c, lp.Aeq, lp.beq, MatrixXd(0, 3), VectorXd(0), lp.lower, lp.upper, x),
            SolveStatus::kOptimal);  // objective pointer is optional
}

TEST(SolveLp, LargerProblemsStrongDuality) {
  // min c^T x s.t. G x >= h, x >= 0 and its dual max h^T y s.t. G^T y <= c, y >= 0, both
  // feasible by construction, so both are optimal with equal objective values.
  for (unsigned seed = 0; seed < 100; ++seed) {
    std::mt19937 rng(seed + 55);
    const Index n = 5 + static_cast<Index>(seed % 16);
    const Index m = 3 + static_cast<Index>(seed % 25);
    const MatrixXd G = randomMatrix(rng, m, n);
    const VectorXd x0 = randomVector(rng, n).cwiseAbs();
    const VectorXd h = G * x0 - randomVector(rng, m).cwiseAbs();
    const VectorXd y0 = randomVector(rng, m).cwiseAbs();
    const VectorXd c = G.transpose() * y0 + randomVector(rng, n).cwiseAbs();
    VectorXd x, y;
    double primal = 0.0, dual = 0.0;
    ASSERT_EQ(solveLp(c, MatrixXd(0, n), VectorXd(0), G, h, VectorXd::Zero(n),
                      VectorXd::Constant(n, kInf), x, &primal),
              SolveStatus::kOptimal)
        << seed;
    // Dual as a minimisation: min -h^T y s.t. -G^T y >= -c, y >= 0.
    ASSERT_EQ(solveLp(-h, MatrixXd(0, m), VectorXd(0), -G.transpose(), -c, VectorXd::Zero(m),
                      VectorXd::Constant(m, kInf), y, &dual),
              SolveStatus::kOptimal)
        << seed;
    EXPECT_NEAR(primal, -dual, 1e-9 * (1.0 + std::abs(primal))) << seed;
    EXPECT_GE((G * x - h).minCoeff(), -1e-9);
    EXPECT_GE(x.minCoeff(), -1e-12);
    EXPECT_GE((c - G.transpose() * y).minCoeff(), -1e-9);
    EXPECT_GE(y.minCoeff(), -1e-12);
  }
}

TEST(SolveLp, EmptyProblems) {
  VectorXd x;
  double obj = 1.0;
  EXPECT_EQ(solveLp(VectorXd(0), MatrixXd(0, 0), VectorXd(0), MatrixXd(0, 0), VectorXd(0),
                    VectorXd(0), VectorXd(0), x, &obj),
            SolveStatus::kOptimal);
  EXPECT_EQ(x.size(), 0);
  EXPECT_EQ(obj, 0.0);
  // 0 >= 1 with no variables.
  EXPECT_EQ(solveLp(VectorXd(0), MatrixXd(0, 0), VectorXd(0), MatrixXd(1, 0), VectorXd::Ones(1),
                    VectorXd(0), VectorXd(0), x, &obj),
            SolveStatus::kInfeasible);
}

}  // namespace
}  // namespace rbsf
