// Tests of the Goldfarb-Idnani QP solver (small_qp.h): KKT conditions on random problems,
// agreement with brute-force active-set enumeration and with leastNormInPolyhedron,
// infeasibility, degenerate constraint sets, the status values and the size checks.

#include "rbsf/dynamics/core/small_qp.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "rbsf/dynamics/core/small_solvers.h"
#include "test_support.h"

namespace rbsf {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// Relative accuracy demanded of the solver's answers (it works to about 1e-14 on these
// well-conditioned problems; its own feasibility tolerance is 1e-10).
constexpr double kTol = 1e-9;

/// A QP in plain dynamic matrices, for the independent computations.
struct Problem {
  MatrixXd H, A_eq, A;
  VectorXd g, b_eq, b;
  Index n() const { return g.size(); }
};

using test::randomMatrix;

VectorXd randomVector(std::mt19937& rng, Index n) { return randomMatrix(rng, n, 1); }

/// max_i |v_i|, 0 for an empty v.
double maxAbs(const VectorXd& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

MatrixXd randomSpd(std::mt19937& rng, Index n) {
  const MatrixXd B = randomMatrix(rng, n, n);
  return B * B.transpose() + 0.1 * MatrixXd::Identity(n, n);
}

/// Random strictly convex QP whose constraints hold at a random point x_f; about a third of
/// the inequality rows pass through x_f, and g is large, so that many rows become active.
Problem randomFeasibleProblem(std::mt19937& rng, Index n, Index me, Index mi) {
  Problem p;
  p.H = randomSpd(rng, n);
  p.g = 5.0 * randomVector(rng, n);
  const VectorXd xf = randomVector(rng, n);
  p.A_eq = randomMatrix(rng, me, n);
  p.b_eq = p.A_eq * xf;
  p.A = randomMatrix(rng, mi, n);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  p.b = p.A * xf;
  for (Index i = 0; i < mi; ++i) {
    if (u(rng) > 0.33) p.b[i] -= u(rng);
  }
  return p;
}

void load(const Problem& p, SmallQp& qp) {
  qp.resize(static_cast<int>(p.n()), static_cast<int>(p.A_eq.rows()), static_cast<int>(p.A.rows()));
  qp.H = p.H;
  qp.g = p.g;
  qp.A_eq = p.A_eq;
  qp.b_eq = p.b_eq;
  qp.A = p.A;
  qp.b = p.b;
  qp.checkSizes();
}

double objectiveOf(const Problem& p, const VectorXd& x) {
  return 0.5 * x.dot(p.H * x) + p.g.dot(x);
}

/// Scale of row i's residual: |b_i| + |a_i|_1 |x|_inf + 1.
double rowScale(const MatrixXd& A, const VectorXd& b, Index i, const VectorXd& x) {
  return 1.0 + std::abs(b[i]) + A.row(i).cwiseAbs().sum() * x.cwiseAbs().maxCoeff();
}

/// Stationarity residual |H x + g - A_eq^T y - A^T lambda|_inf relative to the terms' size.
double stationarityError(const Problem& p, const VectorXd& x, const VectorXd& y,
                         const VectorXd& lambda) {
  const VectorXd res = p.H * x + p.g - p.A_eq.transpose() * y - p.A.transpose() * lambda;
  const VectorXd size = p.H.cwiseAbs() * x.cwiseAbs() + p.g.cwiseAbs() +
                        p.A_eq.transpose().cwiseAbs() * y.cwiseAbs() +
                        p.A.transpose().cwiseAbs() * lambda.cwiseAbs();
  return (res.cwiseAbs().array() / (1.0 + size.array())).maxCoeff();
}

/// The KKT conditions of qp's answer to p, all to kTol (relative).
void expectKkt(const Problem& p, const SmallQp& qp) {
  ASSERT_EQ(qp.status, QpStatus::kOptimal);
  const VectorXd x = qp.x, y = qp.y, lambda = qp.lambda;
  for (Index i = 0; i < p.A_eq.rows(); ++i) {
    EXPECT_LE(std::abs(p.A_eq.row(i).dot(x) - p.b_eq[i]), kTol * rowScale(p.A_eq, p.b_eq, i, x))
        << "equality " << i;
  }
  std::vector<bool> listed(p.A.rows(), false);
  for (int k = 0; k < qp.num_active; ++k) listed[qp.active[k]] = true;
  for (Index i = 0; i < p.A.rows(); ++i) {
    const double slack = p.A.row(i).dot(x) - p.b[i];
    const double scale = rowScale(p.A, p.b, i, x);
    EXPECT_GE(slack, -kTol * scale) << "inequality " << i;
    EXPECT_GE(lambda[i], 0.0) << "inequality " << i;  // exactly
    if (!listed[i]) {
      EXPECT_EQ(lambda[i], 0.0) << "inactive row " << i << " has a multiplier";
    } else {
      EXPECT_LE(std::abs(slack), kTol * scale) << "active row " << i << " does not hold";
    }
    EXPECT_LE(lambda[i] * std::abs(slack), kTol * scale * (1.0 + lambda[i])) << i;
  }
  EXPECT_LE(stationarityError(p, x, y, lambda), kTol);
  const double f = objectiveOf(p, x);
  EXPECT_NEAR(qp.objective, f, 1e-12 * (1.0 + std::abs(f)));
}

TEST(SmallQp, KktOnRandomFeasibleProblems) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pick_n(1, kMaxQpVariables);
  int problems = 0, with_active = 0, with_drops = 0, max_active = 0;
  SmallQp qp;
  for (int trial = 0; trial < 3000; ++trial) {
    // Sizes: the typical control problem (6 variables, ~20 rows) a third of the time, else
    // anything within capacity.
    const bool typical = trial % 3 == 0;
    const int n = typical ? 6 : pick_n(rng);
    const int me = typical ? trial % 2 : std::uniform_int_distribution<int>(0, n - 1)(rng);
    const int mi = typical ? 20 : std::uniform_int_distribution<int>(0, kMaxQpInequalities)(rng);
    const Problem p = randomFeasibleProblem(rng, n, me, mi);
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal) << "trial " << trial;
    expectKkt(p, qp);
    if (::testing::Test::HasFailure()) {
      FAIL() << "trial " << trial << " n " << n << " me " << me << " mi " << mi;
    }
    ++problems;
    with_active += qp.num_active > 0;
    // Each step adds or drops a row: more steps than rows in the final active set means some
    // rows were dropped (partial steps happened).
    with_drops += qp.iterations > qp.num_active + me;
    max_active = std::max(max_active, qp.num_active);
  }
  EXPECT_EQ(problems, 3000);
  EXPECT_GT(with_active, 2500);
  EXPECT_GT(with_drops, 100);
  EXPECT_GE(max_active, 10);
}

TEST(SmallQp, KktOnIllConditionedHessians) {
  // H = Q diag(10^(0..6)) Q^T: the tolerances are relative, the answers still satisfy KKT.
  std::mt19937 rng(12);
  SmallQp qp;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 11;
    Problem p = randomFeasibleProblem(rng, n, trial % 3, 25);
    const Eigen::HouseholderQR<MatrixXd> qr(randomMatrix(rng, n, n));
    const MatrixXd Q = qr.householderQ();
    VectorXd eig(n);
    for (int i = 0; i < n; ++i) eig[i] = std::pow(10.0, 6.0 * i / (n - 1));
    p.H = Q * eig.asDiagonal() * Q.transpose();
    p.H = 0.5 * (p.H + p.H.transpose()).eval();
    p.g *= 100.0;
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal) << trial;
    expectKkt(p, qp);
    if (::testing::Test::HasFailure()) FAIL() << "trial " << trial;
  }
}

// ---------------------------------------------------------------------------------------
// Independent answers

/// Brute force: the KKT point over every active set of at most n - me inequality rows.
/// Returns false when there is none (the problem is infeasible). Non-degenerate random data:
/// the KKT point is unique.
bool bruteForce(const Problem& p, VectorXd& x, VectorXd& y, VectorXd& lambda) {
  const Index n = p.n(), me = p.A_eq.rows(), mi = p.A.rows();
  bool found = false;
  for (unsigned mask = 0; mask < (1u << mi); ++mask) {
    std::vector<Index> rows;
    for (Index i = 0; i < mi; ++i) {
      if (mask & (1u << i)) rows.push_back(i);
    }
    const Index m = me + static_cast<Index>(rows.size());
    if (m > n) continue;
    MatrixXd C(m, n);
    VectorXd d(m);
    C.topRows(me) = p.A_eq;
    d.head(me) = p.b_eq;
    for (size_t k = 0; k < rows.size(); ++k) {
      C.row(me + k) = p.A.row(rows[k]);
      d[me + k] = p.b[rows[k]];
    }
    MatrixXd K = MatrixXd::Zero(n + m, n + m);
    K.topLeftCorner(n, n) = p.H;
    K.topRightCorner(n, m) = -C.transpose();
    K.bottomLeftCorner(m, n) = C;
    VectorXd rhs(n + m);
    rhs << -p.g, d;
    const Eigen::FullPivLU<MatrixXd> lu(K);
    if (lu.rank() < n + m) continue;
    const VectorXd sol = lu.solve(rhs);
    const VectorXd xs = sol.head(n), mu = sol.tail(m);
    if (mu.tail(m - me).size() > 0 && mu.tail(m - me).minCoeff() < -1e-9) continue;
    if (mi > 0 && (p.A * xs - p.b).minCoeff() < -1e-9) continue;
    EXPECT_FALSE(found) << "two KKT points: degenerate data";
    found = true;
    x = xs;
    y = mu.head(me);
    lambda = VectorXd::Zero(mi);
    for (size_t k = 0; k < rows.size(); ++k) lambda[rows[k]] = mu[me + k];
  }
  return found;
}

TEST(SmallQp, MatchesBruteForceActiveSetEnumeration) {
  // Random b (not made feasible): about a fifth of these problems are infeasible, and the
  // solver must say so exactly when enumeration finds no KKT point.
  std::mt19937 rng(21);
  SmallQp qp;
  int solved = 0, infeasible = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    const int n = 1 + trial % 4;
    const int me = (trial / 4) % 2 == 0 ? 0 : std::min(1, n - 1);
    const int mi = 1 + (trial / 8) % 8;
    Problem p;
    p.H = randomSpd(rng, n);
    p.g = 2.0 * randomVector(rng, n);
    p.A_eq = randomMatrix(rng, me, n);
    p.b_eq = randomVector(rng, me);
    p.A = randomMatrix(rng, mi, n);
    p.b = randomVector(rng, mi);
    load(p, qp);
    const QpStatus status = qp.solve();
    VectorXd x, y, lambda;
    if (!bruteForce(p, x, y, lambda)) {
      EXPECT_EQ(status, QpStatus::kInfeasible) << "trial " << trial;
      ++infeasible;
      continue;
    }
    ASSERT_EQ(status, QpStatus::kOptimal) << "trial " << trial;
    ++solved;
    const double scale = 1.0 + x.cwiseAbs().maxCoeff();
    EXPECT_LE((VectorXd(qp.x) - x).cwiseAbs().maxCoeff(), 1e-9 * scale) << "trial " << trial;
    EXPECT_LE(maxAbs(VectorXd(qp.y) - y), 1e-8 * (1.0 + y.cwiseAbs().sum())) << "trial " << trial;
    EXPECT_LE((VectorXd(qp.lambda) - lambda).cwiseAbs().maxCoeff(),
              1e-8 * (1.0 + lambda.cwiseAbs().sum()))
        << "trial " << trial;
    EXPECT_NEAR(qp.objective, objectiveOf(p, x), 1e-10 * (1.0 + std::abs(qp.objective)));
  }
  EXPECT_GT(solved, 800);
  EXPECT_GT(infeasible, 100);
}

TEST(SmallQp, LeastDistanceMatchesLeastNormInPolyhedron) {
  // H = I, g = -x0: the projection of x0 onto the polyhedron; leastNormInPolyhedron (NNLS on
  // the null space of A_eq) gives the least-norm point w of the shifted polyhedron, x = x0 + w.
  std::mt19937 rng(31);
  SmallQp qp;
  int moved = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = trial % 2 == 0 ? 6 : 1 + trial % kMaxQpVariables;
    const int me = trial % 3 == 0 ? 0 : std::min(2, n - 1);
    const int mi = trial % 2 == 0 ? 20 : 40;
    Problem p = randomFeasibleProblem(rng, n, me, mi);
    p.H = MatrixXd::Identity(n, n);
    const VectorXd x0 = 3.0 * randomVector(rng, n);
    p.g = -x0;
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal) << trial;
    VectorXd w;
    ASSERT_EQ(leastNormInPolyhedron(p.A_eq, VectorXd(p.b_eq - p.A_eq * x0), p.A,
                                    VectorXd(p.b - p.A * x0), w),
              SolveStatus::kOptimal);
    const VectorXd projection = x0 + w;
    EXPECT_LE((VectorXd(qp.x) - projection).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + x0.norm()))
        << "trial " << trial;
    EXPECT_NEAR(qp.objective, 0.5 * w.squaredNorm() - 0.5 * x0.squaredNorm(),
                1e-9 * (1.0 + x0.squaredNorm()));
    moved += w.norm() > 1e-3;
  }
  EXPECT_GT(moved, 300);
}

// ---------------------------------------------------------------------------------------
// Infeasibility

/// The documented last iterate: active rows hold, lambda >= 0, stationarity.
void expectLastIterate(const Problem& p, const SmallQp& qp) {
  const VectorXd x = qp.x;
  for (int k = 0; k < qp.num_active; ++k) {
    const Index i = qp.active[k];
    EXPECT_LE(std::abs(p.A.row(i).dot(x) - p.b[i]), kTol * rowScale(p.A, p.b, i, x)) << i;
  }
  for (int i = 0; i < qp.lambda.size(); ++i) EXPECT_GE(qp.lambda[i], 0.0) << i;
  EXPECT_LE(stationarityError(p, x, qp.y, qp.lambda), kTol);
  EXPECT_NEAR(qp.objective, objectiveOf(p, x), 1e-12 * (1.0 + std::abs(qp.objective)));
}

TEST(SmallQp, InfeasibleBoundsAreReported) {
  // x >= 1 and x <= 0.
  Problem p;
  p.H = MatrixXd::Constant(1, 1, 2.0);
  p.g = VectorXd::Constant(1, -1.0);
  p.A_eq.resize(0, 1);
  p.b_eq.resize(0);
  p.A = (MatrixXd(2, 1) << 1.0, -1.0).finished();
  p.b = (VectorXd(2) << 1.0, 0.0).finished();
  SmallQp qp;
  load(p, qp);
  EXPECT_EQ(qp.solve(), QpStatus::kInfeasible);
  EXPECT_EQ(qp.status, QpStatus::kInfeasible);
  // From x = 0.5, row 0 (violated by 0.5) is added: x = 1; then row 1 cannot be added.
  EXPECT_EQ(qp.infeasible_inequality, 1);
  EXPECT_EQ(qp.infeasible_equality, -1);
  ASSERT_EQ(qp.num_active, 1);
  EXPECT_EQ(qp.active[0], 0);
  EXPECT_DOUBLE_EQ(qp.x[0], 1.0);
  expectLastIterate(p, qp);
  EXPECT_STREQ(toString(qp.status), "infeasible");
}

TEST(SmallQp, InfeasibleSetsAreReported) {
  std::mt19937 rng(41);
  SmallQp qp;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 8;
    Problem p = randomFeasibleProblem(rng, n, trial % 2 == 0 ? 0 : std::min(2, n - 1), 15);
    const int kind = trial % 4;
    const VectorXd a = randomVector(rng, n);
    if (kind == 0) {
      // a^T x >= 1 and a^T x <= 0, among feasible rows (random positions).
      p.A.row(3) = a;
      p.b[3] = 1.0;
      p.A.row(9) = -a;
      p.b[9] = 0.0;
    } else if (kind == 1) {
      // a zero row that asks 0 >= 1
      p.A.row(5).setZero();
      p.b[5] = 1.0;
    } else if (kind == 2) {
      // the rows a_1, a_2 and -(a_1 + a_2) with b summing to a positive number
      const VectorXd c = randomVector(rng, n);
      p.A.row(2) = a;
      p.A.row(7) = c;
      p.A.row(11) = -(a + c);
      p.b[2] = 0.5;
      p.b[7] = 0.5;
      p.b[11] = -0.5;
    } else {
      // an inequality contradicts an added equality: a^T x = 0 and a^T x >= 1
      const Index me = p.A_eq.rows() + 1;
      ASSERT_LE(me, n);
      p.A_eq.conservativeResize(me, n);
      p.b_eq.conservativeResize(me);
      p.A_eq.row(me - 1) = a.transpose();
      p.b_eq[me - 1] = 0.0;
      p.A.row(4) = a;
      p.b[4] = 1.0;
    }
    load(p, qp);
    EXPECT_EQ(qp.solve(), QpStatus::kInfeasible) << "trial " << trial << " kind " << kind;
    EXPECT_EQ(qp.infeasible_equality, -1);
    EXPECT_GE(qp.infeasible_inequality, 0);
    expectLastIterate(p, qp);
    if (::testing::Test::HasFailure()) FAIL() << "trial " << trial << " kind " << kind;
  }
}

TEST(SmallQp, InconsistentEqualitiesAreReported) {
  // x_0 + x_1 = 1, x_0 - x_1 = 0, 2 x_0 = 3 (dependent on the first two, inconsistent).
  Problem p;
  p.H = MatrixXd::Identity(2, 2);
  p.g = VectorXd::Zero(2);
  p.A_eq = (MatrixXd(3, 2) << 1, 1, 1, -1, 2, 0).finished();
  p.b_eq = (VectorXd(3) << 1, 0, 3).finished();
  p.A.resize(0, 2);
  p.b.resize(0);
  SmallQp qp;
  load(p, qp);
  EXPECT_EQ(qp.solve(), QpStatus::kInfeasible);
  EXPECT_EQ(qp.infeasible_equality, 2);
  EXPECT_EQ(qp.infeasible_inequality, -1);
  // x holds the first two equalities.
  EXPECT_NEAR(qp.x[0], 0.5, 1e-15);
  EXPECT_NEAR(qp.x[1], 0.5, 1e-15);
  expectLastIterate(p, qp);
  // Made consistent (2 x_0 = 1), the row is redundant: skipped with a zero multiplier.
  qp.b_eq[2] = 1.0;
  p.b_eq[2] = 1.0;
  EXPECT_EQ(qp.solve(), QpStatus::kOptimal);
  EXPECT_EQ(qp.y[2], 0.0);
  expectKkt(p, qp);
}

// ---------------------------------------------------------------------------------------
// Degenerate and special cases

TEST(SmallQp, NoConstraintsGivesTheUnconstrainedMinimum) {
  std::mt19937 rng(51);
  SmallQp qp;
  for (int n = 1; n <= kMaxQpVariables; ++n) {
    const Problem p = randomFeasibleProblem(rng, n, 0, 0);
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal);
    const VectorXd x = p.H.llt().solve(-p.g);
    EXPECT_LE((VectorXd(qp.x) - x).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + x.norm())) << n;
    EXPECT_NEAR(qp.objective, 0.5 * p.g.dot(x), 1e-10 * (1.0 + std::abs(qp.objective)));
    EXPECT_EQ(qp.iterations, 0);
    EXPECT_EQ(qp.num_active, 0);
  }
}

TEST(SmallQp, EqualityOnlyMatchesTheKktSystem) {
  std::mt19937 rng(52);
  SmallQp qp;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % kMaxQpVariables;
    const int me = 1 + trial % n;  // up to n: x then fully determined
    Problem p = randomFeasibleProblem(rng, n, me, 0);
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal);
    MatrixXd K = MatrixXd::Zero(n + me, n + me);
    K.topLeftCorner(n, n) = p.H;
    K.topRightCorner(n, me) = -p.A_eq.transpose();
    K.bottomLeftCorner(me, n) = p.A_eq;
    VectorXd rhs(n + me);
    rhs << -p.g, p.b_eq;
    const VectorXd sol = K.fullPivLu().solve(rhs);
    const double cond_guard = 1e-8 * (1.0 + sol.cwiseAbs().maxCoeff());
    EXPECT_LE((VectorXd(qp.x) - sol.head(n)).cwiseAbs().maxCoeff(), cond_guard) << trial;
    EXPECT_LE(maxAbs(VectorXd(qp.y) - sol.tail(me)), cond_guard) << trial;
    EXPECT_EQ(qp.iterations, me);
    expectKkt(p, qp);
  }
}

TEST(SmallQp, DependentEqualityRowsAreSkipped) {
  // 16 variables, 16 equality rows of rank 10: rows 10..15 are sums and multiples of
  // earlier rows (consistent).
  std::mt19937 rng(53);
  Problem p = randomFeasibleProblem(rng, 16, 16, 30);
  for (int i = 10; i < 16; ++i) {
    p.A_eq.row(i) = (i - 8) * p.A_eq.row(i - 10) - p.A_eq.row(i - 9);
    p.b_eq[i] = (i - 8) * p.b_eq[i - 10] - p.b_eq[i - 9];
  }
  SmallQp qp;
  load(p, qp);
  ASSERT_EQ(qp.solve(), QpStatus::kOptimal);
  for (int i = 10; i < 16; ++i) EXPECT_EQ(qp.y[i], 0.0) << i;
  expectKkt(p, qp);
}

TEST(SmallQp, RowsActiveAtTheUnconstrainedMinimumNeedNoStep) {
  std::mt19937 rng(54);
  Problem p = randomFeasibleProblem(rng, 6, 0, 20);
  const VectorXd x_free = p.H.llt().solve(-p.g);
  p.b = p.A * x_free;  // every row passes through the unconstrained minimum
  for (int i = 10; i < 20; ++i) p.b[i] -= 1.0;
  SmallQp qp;
  load(p, qp);
  ASSERT_EQ(qp.solve(), QpStatus::kOptimal);
  EXPECT_EQ(qp.iterations, 0);
  EXPECT_EQ(qp.num_active, 0);
  EXPECT_EQ(VectorXd(qp.lambda).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE((VectorXd(qp.x) - x_free).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + x_free.norm()));
  expectKkt(p, qp);
}

TEST(SmallQp, DuplicatedAndScaledRowsGiveTheSameSolution) {
  std::mt19937 rng(55);
  SmallQp qp, dup;
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 + trial % 8;
    const Problem p = randomFeasibleProblem(rng, n, trial % 2, 12);
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal);
    // Each row three times: as given, doubled (2a, 2b) and once more as given.
    Problem q = p;
    q.A.resize(36, n);
    q.b.resize(36);
    q.A << p.A, 2.0 * p.A, p.A;
    q.b << p.b, 2.0 * p.b, p.b;
    load(q, dup);
    ASSERT_EQ(dup.solve(), QpStatus::kOptimal) << trial;
    expectKkt(q, dup);
    EXPECT_LE((VectorXd(dup.x) - VectorXd(qp.x)).cwiseAbs().maxCoeff(),
              1e-9 * (1.0 + VectorXd(qp.x).norm()))
        << trial;
    EXPECT_NEAR(dup.objective, qp.objective, 1e-9 * (1.0 + std::abs(qp.objective)));
    // The copies share the original row's multiplier: lambda_i = l_i + 2 l'_i + l''_i.
    for (int i = 0; i < 12; ++i) {
      EXPECT_NEAR(dup.lambda[i] + 2.0 * dup.lambda[12 + i] + dup.lambda[24 + i], qp.lambda[i],
                  1e-8 * (1.0 + VectorXd(qp.lambda).sum()))
          << trial << " row " << i;
    }
    compared += qp.num_active > 0;
  }
  EXPECT_GT(compared, 150);
}

TEST(SmallQp, DegenerateVertexWithMoreActiveRowsThanVariables) {
  // n = 2: x >= 0, y >= 0, x + y >= 0, x + 2 y >= 0, all through the origin; the free
  // minimum (-1, -2) is outside: the solution is the origin with 4 rows through it.
  Problem p;
  p.H = MatrixXd::Identity(2, 2);
  p.g = (VectorXd(2) << 1.0, 2.0).finished();
  p.A_eq.resize(0, 2);
  p.b_eq.resize(0);
  p.A = (MatrixXd(4, 2) << 1, 0, 0, 1, 1, 1, 1, 2).finished();
  p.b = VectorXd::Zero(4);
  SmallQp qp;
  load(p, qp);
  ASSERT_EQ(qp.solve(), QpStatus::kOptimal);
  EXPECT_LE(VectorXd(qp.x).norm(), 1e-14);
  expectKkt(p, qp);

  // The same in 6 variables: 14 random rows through x_f, the free minimum far away.
  std::mt19937 rng(56);
  for (int trial = 0; trial < 100; ++trial) {
    Problem r = randomFeasibleProblem(rng, 6, trial % 2, 14);
    const VectorXd xf = randomVector(rng, 6);
    r.b = r.A * xf;
    r.b_eq = r.A_eq * xf;
    r.g = 50.0 * randomVector(rng, 6);
    load(r, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal) << trial;
    expectKkt(r, qp);
  }
}

TEST(SmallQp, NotConvexIsReported) {
  SmallQp qp(2, 0, 1);
  qp.A << 1.0, 1.0;
  qp.b << 0.0;
  qp.g << 1.0, 1.0;
  const std::vector<Eigen::Matrix2d> hessians = {
      (Eigen::Matrix2d() << 1, 0, 0, -1).finished(),  // indefinite
      Eigen::Matrix2d::Zero(),
      (Eigen::Matrix2d() << 1, 1, 1, 1).finished(),      // singular
      (Eigen::Matrix2d() << 1, 0, 0, 1e-14).finished(),  // numerically singular
      (Eigen::Matrix2d() << -1, 0, 0, -1).finished(),    // negative definite
      (Eigen::Matrix2d() << 1, 0, 0, std::nan("")).finished(),
  };
  for (const auto& h : hessians) {
    qp.H = h;
    EXPECT_EQ(qp.solve(), QpStatus::kNotConvex) << h;
    EXPECT_TRUE(std::isnan(qp.objective));
    EXPECT_EQ(VectorXd(qp.x).norm(), 0.0);
  }
  qp.H = Eigen::Matrix2d::Identity();
  EXPECT_EQ(qp.solve(), QpStatus::kOptimal);
  // Only the lower triangle is read: garbage above the diagonal does not matter.
  qp.H(0, 1) = 1e9;
  EXPECT_EQ(qp.solve(), QpStatus::kOptimal);
  EXPECT_NEAR(qp.x[0], 0.0, 1e-15);  // the projection of -g = (-1, -1) onto x_0 + x_1 >= 0
  EXPECT_NEAR(qp.x[1], 0.0, 1e-15);
  EXPECT_NEAR(qp.lambda[0], 1.0, 1e-15);
}

TEST(SmallQp, IterationLimitGivesALowerBoundAndAValidIterate) {
  std::mt19937 rng(61);
  SmallQp qp;
  int limited = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Problem p = randomFeasibleProblem(rng, 6 + trial % 7, trial % 2, 40);
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal);
    const double optimum = qp.objective;
    const int steps = qp.iterations;
    // The equalities are always added (they take me steps); the limit applies from then on.
    for (int limit = static_cast<int>(p.A_eq.rows()); limit < steps; ++limit) {
      qp.max_iterations = limit;
      ASSERT_EQ(qp.solve(), QpStatus::kMaxIterations);
      EXPECT_EQ(qp.iterations, limit);
      EXPECT_LE(qp.objective, optimum + 1e-12 * (1.0 + std::abs(optimum)));
      expectLastIterate(p, qp);
      ++limited;
    }
    qp.max_iterations = steps;
    EXPECT_EQ(qp.solve(), QpStatus::kOptimal);
    qp.max_iterations = 1000;
  }
  EXPECT_GT(limited, 500);
}

TEST(SmallQp, SolvesAreDeterministic) {
  std::mt19937 rng(62);
  const Problem p = randomFeasibleProblem(rng, 9, 2, 60);
  SmallQp a, b;
  load(p, a);
  load(p, b);
  ASSERT_EQ(a.solve(), QpStatus::kOptimal);
  // b solves another problem first: nothing of it may leak into the next answer.
  const Problem other = randomFeasibleProblem(rng, 9, 2, 60);
  b.H = other.H;
  b.g = other.g;
  b.A_eq = other.A_eq;
  b.b_eq = other.b_eq;
  b.A = other.A;
  b.b = other.b;
  ASSERT_EQ(b.solve(), QpStatus::kOptimal);
  b.H = p.H;
  b.g = p.g;
  b.A_eq = p.A_eq;
  b.b_eq = p.b_eq;
  b.A = p.A;
  b.b = p.b;
  ASSERT_EQ(b.solve(), QpStatus::kOptimal);
  EXPECT_EQ(std::memcmp(a.x.data(), b.x.data(), sizeof(double) * 9), 0);
  EXPECT_EQ(std::memcmp(a.lambda.data(), b.lambda.data(), sizeof(double) * 60), 0);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.objective, b.objective);
}

TEST(SmallQp, SizesAreChecked) {
  EXPECT_THROW(SmallQp(0, 0, 0), std::invalid_argument);
  EXPECT_THROW(SmallQp(kMaxQpVariables + 1, 0, 0), std::invalid_argument);
  EXPECT_THROW(SmallQp(3, kMaxQpEqualities + 1, 0), std::invalid_argument);
  EXPECT_THROW(SmallQp(3, 0, kMaxQpInequalities + 1), std::invalid_argument);
  EXPECT_THROW(SmallQp(3, -1, 0), std::invalid_argument);
  SmallQp qp(kMaxQpVariables, kMaxQpEqualities, kMaxQpInequalities);
  EXPECT_NO_THROW(qp.checkSizes());
  qp.resize(4, 1, 5);
  EXPECT_NO_THROW(qp.checkSizes());
  qp.A.resize(5, 3);
  EXPECT_THROW(qp.checkSizes(), std::invalid_argument);
  qp.resize(4, 1, 5);
  qp.b_eq.resize(2);
  EXPECT_THROW(qp.checkSizes(), std::invalid_argument);
  qp.resize(4, 1, 5);
  qp.feasibility_tolerance = -1.0;
  EXPECT_THROW(qp.checkSizes(), std::invalid_argument);
}

TEST(SmallQp, FullCapacityProblems) {
  std::mt19937 rng(63);
  SmallQp qp;
  for (int trial = 0; trial < 50; ++trial) {
    const Problem p = randomFeasibleProblem(rng, kMaxQpVariables, 4, kMaxQpInequalities);
    load(p, qp);
    ASSERT_EQ(qp.solve(), QpStatus::kOptimal) << trial;
    expectKkt(p, qp);
  }
}

}  // namespace
}  // namespace rbsf
