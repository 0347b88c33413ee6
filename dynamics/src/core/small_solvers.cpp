#include "rbsf/dynamics/core/small_solvers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

namespace rbsf {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("rbsf small solvers: ") + what);
}

// ---------------------------------------------------------------------------------------
// LCP

// Relative tolerance on the sign tests of the pivoting. A component that is zero in exact
// arithmetic (degenerate contact) comes out as +-cond(A_SS) * eps; without a tolerance the
// least-index rule could flip it in and out forever. 1e-11 covers cond(A_SS) up to ~1e4.
constexpr double kLcpTol = 1e-11;

// ---------------------------------------------------------------------------------------
// LDP / least-norm

// Singular values below this fraction of the largest one count as zero when taking the rank
// of A_eq: rows dependent up to rounding are accepted as dependent.
constexpr double kRankTol = 1e-10;
// Relative tolerance of the final feasibility verification of leastNormInPolyhedron().
constexpr double kFeasTol = 1e-9;

// ---------------------------------------------------------------------------------------
// Simplex

constexpr double kPivotTol = 1e-9;   // smallest usable pivot in a row-normalised tableau
constexpr double kCostTol = 1e-9;    // reduced cost counted as negative (cost normalised)
constexpr double kPhase1Tol = 1e-9;  // relative infeasibility accepted at the end of phase 1

// Row-major: a pivot is row operations, contiguous this way (2-3x faster than column-major).
using TableauMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Dense simplex tableau: rows 0..m-1 are constraints, row m holds the reduced costs with
/// -(objective value) in the last column. Column `cols()-1` is the right-hand side.
class Tableau {
 public:
  Tableau(TableauMatrix t, std::vector<Index> basis) : t_(std::move(t)), basis_(std::move(basis)) {}

  Index rows() const { return t_.rows() - 1; }
  Index vars() const { return t_.cols() - 1; }
  TableauMatrix& t() { return t_; }
  const TableauMatrix& t() const { return t_; }
  std::vector<Index>& basis() { return basis_; }

  void pivot(Index r, Index c) {
    t_.row(r) /= t_(r, c);
    for (Index i = 0; i < t_.rows(); ++i) {
      if (i == r) continue;
      const double f = t_(i, c);
      if (f != 0.0) t_.row(i) -= f * t_.row(r);
    }
    // Keep the pivot column an exact unit vector so later Bland tests are not fooled.
    t_.col(c).setZero();
    t_(r, c) = 1.0;
    basis_[static_cast<std::size_t>(r)] = c;
    // Rounding may push a zero right-hand side slightly negative; the basis is primal
    // feasible in exact arithmetic, so clamp to keep the ratio test meaningful.
    for (Index i = 0; i < rows(); ++i) {
      if (t_(i, vars()) < 0.0 && t_(i, vars()) > -kPivotTol) t_(i, vars()) = 0.0;
    }
  }

  enum class Result { kOptimal, kUnbounded };

  /// Primal simplex with Bland's rule over columns [0, allowed): the entering variable is
  /// the lowest-index one with negative reduced cost, the leaving one the lowest-index
  /// basic variable among the minimum-ratio rows. This never cycles, so degenerate
  /// problems terminate.
  Result run(Index allowed) {
    const Index m = rows();
    const Index rhs = vars();
    // Bland's rule visits each basis at most once; the limit is a guard against rounding.
    const long limit = 50 * (m + t_.cols()) + 1000;
    for (long iter = 0;; ++iter) {
      if (iter > limit) throw std::runtime_error("solveLp: simplex iteration limit reached");
      Index enter = -1;
      for (Index j = 0; j < allowed; ++j) {
        if (t_(m, j) < -kCostTol) {
          enter = j;
          break;
        }
      }
      if (enter < 0) return Result::kOptimal;
      Index leave = -1;
      double best = kInf;
      for (Index i = 0; i < m; ++i) {
        const double a = t_(i, enter);
        if (a <= kPivotTol) continue;
        const double ratio = t_(i, rhs) / a;
        const double tie = 1e-12 * (1.0 + std::abs(best));
        if (leave < 0 || ratio < best - tie ||
            (ratio <= best + tie &&
             basis_[static_cast<std::size_t>(i)] < basis_[static_cast<std::size_t>(leave)])) {
          if (leave < 0 || ratio < best - tie) best = ratio;
          leave = i;
        }
      }
      if (leave < 0) return Result::kUnbounded;
      pivot(leave, enter);
    }
  }

 private:
  TableauMatrix t_;
  std::vector<Index> basis_;
};

}  // namespace

// =======================================================================================

LcpStatus solveLcp(const MatCC& A, const VecC& p, VecC& z, VecC& w) {
  const Index n = p.size();
  require(A.rows() == n && A.cols() == n, "solveLcp: A must be n x n with n = p.size()");
  LcpStatus status;
  z.setZero(n);
  w = p;
  if (n == 0) {
    status.solved = true;
    return status;
  }

  const double aScale = A.cwiseAbs().maxCoeff();
  const double pScale = p.cwiseAbs().maxCoeff();
  // The Delassus matrix is symmetric; LDLT (with its pseudo-inverse of zero pivots) also
  // copes with redundant contacts. A general P-matrix gets LU instead.
  const bool symmetric =
      (A - A.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * std::max(aScale, kEps);

  std::array<bool, kMaxFingers> active;
  active.fill(true);
  std::array<Index, kMaxFingers> idx{};
  MatCC Ass;
  VecC rhs;
  VecC zs;
  Eigen::LDLT<MatCC> ldlt;
  Eigen::PartialPivLU<MatCC> lu;
  // Murty's least-index method visits each of the 2^n principal bases at most once.
  const int limit = (1 << n) + static_cast<int>(n);

  for (;;) {
    Index k = 0;
    for (Index i = 0; i < n; ++i) {
      if (active[static_cast<std::size_t>(i)]) idx[static_cast<std::size_t>(k++)] = i;
    }
    z.setZero();
    if (k > 0) {
      Ass.resize(k, k);
      rhs.resize(k);
      for (Index a = 0; a < k; ++a) {
        const Index ia = idx[static_cast<std::size_t>(a)];
        rhs(a) = -p(ia);
        for (Index b = 0; b < k; ++b) Ass(a, b) = A(ia, idx[static_cast<std::size_t>(b)]);
      }
      if (symmetric) {
        ldlt.compute(Ass);
        zs = ldlt.solve(rhs);
      } else {
        lu.compute(Ass);
        zs = lu.solve(rhs);
      }
      for (Index a = 0; a < k; ++a) z(idx[static_cast<std::size_t>(a)]) = zs(a);
    }
    w.noalias() = A * z;
    w += p;

    const double zMax = z.cwiseAbs().maxCoeff();
    const double zTol = kLcpTol * zMax;
    const double wTol = kLcpTol * (pScale + aScale * zMax);
    Index flip = -1;
    for (Index i = 0; i < n; ++i) {
      const bool in = active[static_cast<std::size_t>(i)];
      if ((in && z(i) < -zTol) || (!in && w(i) < -wTol)) {
        flip = i;
        break;
      }
    }
    if (flip < 0) break;
    if (status.pivots >= limit) return status;  // not a P-matrix (or hopelessly conditioned)
    active[static_cast<std::size_t>(flip)] = !active[static_cast<std::size_t>(flip)];
    ++status.pivots;
  }

  // Make complementarity exact; the values changed are within the tolerance above.
  for (Index i = 0; i < n; ++i) {
    if (active[static_cast<std::size_t>(i)]) {
      z(i) = std::max(z(i), 0.0);
      w(i) = 0.0;
    } else {
      z(i) = 0.0;
      w(i) = std::max(w(i), 0.0);
    }
  }
  status.solved = true;
  return status;
}

// =======================================================================================

namespace {

/// Lawson-Hanson NNLS on any column-capacity: the work vectors and the passive columns'
/// copy take E's compile-time maximum sizes, so a fixed-capacity E (Mat3C) keeps them on
/// the stack, and MatrixXd on the heap.
template <class MatE, class VecF, class VecX>
bool nnls(const MatE& E, const VecF& f, VecX& x) {
  constexpr int kMaxCols = MatE::MaxColsAtCompileTime;
  using Work = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxCols, 1>;
  using Flags = Eigen::Matrix<Index, Eigen::Dynamic, 1, 0, kMaxCols, 1>;
  using Columns = Eigen::Matrix<double, MatE::RowsAtCompileTime, Eigen::Dynamic, 0,
                                MatE::MaxRowsAtCompileTime, kMaxCols>;
  const Index m = E.rows();
  const Index n = E.cols();
  require(f.size() == m, "solveNnls: f.size() must equal E.rows()");
  x.setZero(n);
  if (n == 0 || m == 0) return true;

  // Scale of the dual vector w = E^T (f - E x): |f - E x| <= |f| throughout, since every
  // iterate improves on x = 0 (the same choice as lsqnonneg, times |f| for scale invariance).
  const double tol = 10.0 * kEps * static_cast<double>(std::max(m, n)) *
                     E.cwiseAbs().colwise().sum().maxCoeff() * f.norm();

  Flags passive = Flags::Zero(n);
  Flags cols(n);
  Work zP;
  Columns Ep;

  // Least squares on the passive columns; returns the full-length solution in `out`.
  auto solvePassive = [&](Work& out) {
    Index k = 0;
    for (Index j = 0; j < n; ++j) {
      if (passive(j)) cols(k++) = j;
    }
    Ep.resize(m, k);
    for (Index c = 0; c < k; ++c) Ep.col(c) = E.col(cols(c));
    zP = Ep.colPivHouseholderQr().solve(f);
    out.setZero(n);
    for (Index c = 0; c < k; ++c) out(cols(c)) = zP(c);
  };

  // Lawson & Hanson's 3n on the outer iterations (each inner step removes a passive
  // variable, so inner steps never outnumber outer ones), plus slack for rejected trials.
  const long limit = 3 * n + 30;
  long iterations = 0;
  Work w(n);
  Work z(n);
  Flags rejected = Flags::Zero(n);

  for (;;) {
    w.noalias() = E.transpose() * (f - E * x);
    // Step 2/5 of L&H: pick the active column with the most positive dual.
    Index t = -1;
    double best = tol;
    for (Index j = 0; j < n; ++j) {
      if (!passive(j) && !rejected(j) && w(j) > best) {
        best = w(j);
        t = j;
      }
    }
    if (t < 0) return true;
    if (++iterations > limit) return false;

    passive(t) = 1;
    solvePassive(z);
    if (z(t) <= 0.0) {
      // Rounding made the dual look positive although the column cannot enter with a
      // positive value (L&H ch. 23, the test after step 6): reject it until x changes,
      // otherwise the same column would be chosen forever.
      passive(t) = 0;
      rejected(t) = 1;
      continue;
    }
    rejected.setZero();

    // Inner loop: step back along x -> z until every passive variable is positive.
    for (;;) {
      double alpha = kInf;
      Index hit = -1;
      for (Index j = 0; j < n; ++j) {
        if (passive(j) && z(j) <= 0.0) {
          const double a = x(j) / (x(j) - z(j));
          if (a < alpha) {
            alpha = a;
            hit = j;
          }
        }
      }
      if (hit < 0) {
        x = z;
        break;
      }
      x += alpha * (z - x);
      // The variable that defined alpha leaves the passive set, and so does any other that
      // reached zero up to rounding.
      const double xTol = 10.0 * kEps * x.cwiseAbs().maxCoeff();
      for (Index j = 0; j < n; ++j) {
        if (passive(j) && (j == hit || x(j) <= xTol)) {
          passive(j) = 0;
          x(j) = 0.0;
        }
      }
      solvePassive(z);
    }
  }
}

}  // namespace

bool solveNnls(const MatrixXd& E, const VectorXd& f, VectorXd& x) { return nnls(E, f, x); }

bool solveNnls(const Mat3C& E, const Eigen::Vector3d& f, VecC& x) { return nnls(E, f, x); }

// =======================================================================================

SolveStatus leastNormInPolyhedron(const MatrixXd& A_eq, const VectorXd& b_eq, const MatrixXd& G,
                                  const VectorXd& h, VectorXd& x, double rhs_scale) {
  const Index r = A_eq.rows();
  const Index p = G.rows();
  const Index n = std::max(A_eq.cols(), G.cols());
  require(b_eq.size() == r, "leastNormInPolyhedron: b_eq.size() must equal A_eq.rows()");
  require(h.size() == p, "leastNormInPolyhedron: h.size() must equal G.rows()");
  require(r == 0 || A_eq.cols() == n, "leastNormInPolyhedron: A_eq and G column counts differ");
  require(p == 0 || G.cols() == n, "leastNormInPolyhedron: A_eq and G column counts differ");

  // Particular least-norm solution x0 and orthonormal null-space basis Z of A_eq. Then
  // x = x0 + Z y with x0 in the row space, so |x|^2 = |x0|^2 + |y|^2 and the problem is
  // least-distance programming in y.
  VectorXd x0 = VectorXd::Zero(n);
  MatrixXd Z;
  double x_noise = 0.0;  // how far rounding of b_eq (at rhs_scale) can move x
  if (r > 0 && n > 0) {
    Eigen::JacobiSVD<MatrixXd> svd(A_eq, Eigen::ComputeThinU | Eigen::ComputeFullV);
    const VectorXd& s = svd.singularValues();
    Index rank = 0;
    const double cut = kRankTol * (s.size() > 0 ? s(0) : 0.0);
    while (rank < s.size() && s(rank) > cut) ++rank;
    if (rank > 0) {
      x_noise = rhs_scale / s(rank - 1);
      x0 = svd.matrixV().leftCols(rank) *
           (svd.matrixU().leftCols(rank).transpose() * b_eq).cwiseQuotient(s.head(rank));
    }
    Z = svd.matrixV().rightCols(n - rank);
  } else {
    Z = MatrixXd::Identity(n, n);
  }
  if (r > 0) {
    const double resid = (A_eq * x0 - b_eq).norm();
    const double scale = (n > 0 ? A_eq.norm() * x0.norm() : 0.0) + b_eq.norm() + rhs_scale;
    if (!(resid <= kFeasTol * scale)) return SolveStatus::kInfeasible;
  }

  // y = 0 (x = x0) when the inequalities already hold there or there are none.
  VectorXd y = VectorXd::Zero(Z.cols());
  if (p > 0 && Z.cols() > 0) {
    // LDP: min |y| s.t. Gz y >= hz. Normalise rows (the feasible set is unchanged) so that
    // hz_i is the signed distance of constraint i from the origin.
    MatrixXd Gz = G * Z;
    VectorXd hz = h - G * x0;
    // Rounding in b_eq moves the affine set by up to x_noise; a cone's apex may then lie
    // just off it. Relax each row by what that movement can change it.
    for (Index i = 0; i < p; ++i) hz(i) -= kFeasTol * G.row(i).norm() * x_noise;
    std::vector<Index> keep;
    for (Index i = 0; i < p; ++i) {
      const double nrm = Gz.row(i).norm();
      if (nrm <= kRankTol * G.row(i).norm()) {
        // The row is constant on the affine hull of A_eq x = b_eq: 0 >= hz_i, checked below.
        continue;
      }
      Gz.row(i) /= nrm;
      hz(i) /= nrm;
      keep.push_back(i);
    }
    const double hzMax = keep.empty() ? 0.0 : hz(keep).maxCoeff();
    if (hzMax > 0.0) {
      // Scale y so the farthest half-space is at distance 1: the NNLS residual below then
      // has |res|^2 = 1 / (1 + |y|^2), making the infeasibility test scale-free.
      const Index q = static_cast<Index>(keep.size());
      const Index k = Z.cols();
      MatrixXd Eldp(k + 1, q);
      for (Index c = 0; c < q; ++c) {
        Eldp.col(c).head(k) = Gz.row(keep[static_cast<std::size_t>(c)]).transpose();
        Eldp(k, c) = hz(keep[static_cast<std::size_t>(c)]) / hzMax;
      }
      VectorXd fl = VectorXd::Zero(k + 1);
      fl(k) = 1.0;
      // Lawson & Hanson ch. 23: the LDP dual is NNLS(E, f) with E = [Gz^T; hz^T]. A zero
      // residual certifies infeasibility; otherwise y = -res(0:k) / res(k).
      VectorXd u;
      if (!solveNnls(Eldp, fl, u)) return SolveStatus::kInfeasible;
      const VectorXd res = Eldp * u - fl;
      if (!(res.norm() > 1e-12) || !(res(k) < 0.0)) return SolveStatus::kInfeasible;
      y = -res.head(k) / res(k) * hzMax;

      // res(k) = -|res|^2 is small when |y| is large compared with the constraint
      // distances, costing relative accuracy. By the KKT conditions y = Gz_S^T u_S on the
      // support S of u, i.e. y is the least-norm solution of Gz_S y = hz_S: recompute it
      // from that system and keep it if it is no less feasible.
      std::vector<Index> support;
      for (Index c = 0; c < q; ++c) {
        if (u(c) > 0.0) support.push_back(keep[static_cast<std::size_t>(c)]);
      }
      if (!support.empty()) {
        const MatrixXd Gs = Gz(support, Eigen::all);
        const VectorXd ys = Gs.completeOrthogonalDecomposition().solve(hz(support));
        auto worst = [&](const VectorXd& v) {
          double viol = 0.0;
          for (Index i : keep) viol = std::max(viol, hz(i) - Gz.row(i).dot(v));
          return viol;
        };
        if (worst(ys) <= std::max(worst(y), 1e-14 * hzMax)) y = ys;
      }
    }
  }

  x = x0 + Z * y;

  // Verify: the rank cut-off and NNLS tolerances must not hide an infeasible answer.
  if (r > 0) {
    const double resid = (A_eq * x - b_eq).norm();
    if (!(resid <= kFeasTol * (A_eq.norm() * x.norm() + b_eq.norm() + rhs_scale))) {
      return SolveStatus::kInfeasible;
    }
  }
  for (Index i = 0; i < p; ++i) {
    const double tol = kFeasTol * (G.row(i).norm() * (x.norm() + x_noise) + std::abs(h(i)));
    if (!(G.row(i).dot(x) >= h(i) - tol)) return SolveStatus::kInfeasible;
  }
  return SolveStatus::kOptimal;
}

// =======================================================================================

SolveStatus solveLp(const VectorXd& c, const MatrixXd& A_eq, const VectorXd& b_eq,
                    const MatrixXd& G, const VectorXd& h, const VectorXd& lower,
                    const VectorXd& upper, VectorXd& x, double* objective) {
  const Index n = c.size();
  const Index me = A_eq.rows();
  const Index mg = G.rows();
  require(b_eq.size() == me && h.size() == mg, "solveLp: right-hand side sizes");
  require(me == 0 || A_eq.cols() == n, "solveLp: A_eq.cols() must equal c.size()");
  require(mg == 0 || G.cols() == n, "solveLp: G.cols() must equal c.size()");
  require(lower.size() == n && upper.size() == n, "solveLp: bound sizes must equal c.size()");
  for (Index j = 0; j < n; ++j) {
    require(!std::isnan(lower(j)) && !std::isnan(upper(j)), "solveLp: NaN bound");
    if (lower(j) > upper(j) || lower(j) == kInf || upper(j) == -kInf) {
      return SolveStatus::kInfeasible;
    }
  }

  // Standard form: x = d + T xs with xs >= 0. Finite lower bound: shift; only an upper
  // bound: reflect; free: split into xs+ - xs-. Upper bounds on shifted variables become
  // rows with slacks; G rows get surplus variables.
  std::vector<Index> firstCol(static_cast<std::size_t>(n));
  VectorXd d = VectorXd::Zero(n);
  Index ns = 0;  // structural standard-form columns
  Index nBoundRows = 0;
  for (Index j = 0; j < n; ++j) {
    firstCol[static_cast<std::size_t>(j)] = ns;
    const bool lo = std::isfinite(lower(j));
    const bool up = std::isfinite(upper(j));
    if (lo) {
      d(j) = lower(j);
      ns += 1;
      if (up) ++nBoundRows;
    } else if (up) {
      d(j) = upper(j);
      ns += 1;
    } else {
      ns += 2;
    }
  }
  MatrixXd T = MatrixXd::Zero(n, ns);
  for (Index j = 0; j < n; ++j) {
    const Index col = firstCol[static_cast<std::size_t>(j)];
    if (std::isfinite(lower(j))) {
      T(j, col) = 1.0;
    } else if (std::isfinite(upper(j))) {
      T(j, col) = -1.0;
    } else {
      T(j, col) = 1.0;
      T(j, col + 1) = -1.0;
    }
  }

  const Index m = me + mg + nBoundRows;
  const Index N = ns + mg + nBoundRows;  // structural + surplus + slack columns
  MatrixXd A = MatrixXd::Zero(m, N);
  VectorXd b(m);
  if (me > 0) {
    A.block(0, 0, me, ns) = A_eq * T;
    b.head(me) = b_eq - A_eq * d;
  }
  if (mg > 0) {
    A.block(me, 0, mg, ns) = G * T;
    A.block(me, ns, mg, mg) = -MatrixXd::Identity(mg, mg);
    b.segment(me, mg) = h - G * d;
  }
  {
    Index row = me + mg;
    for (Index j = 0; j < n; ++j) {
      if (std::isfinite(lower(j)) && std::isfinite(upper(j))) {
        A(row, firstCol[static_cast<std::size_t>(j)]) = 1.0;
        A(row, ns + mg + (row - me - mg)) = 1.0;
        b(row) = upper(j) - lower(j);
        ++row;
      }
    }
  }
  VectorXd cs = VectorXd::Zero(N);
  cs.head(ns) = T.transpose() * c;
  const double cMax = N > 0 ? cs.cwiseAbs().maxCoeff() : 0.0;
  if (cMax > 0.0) cs /= cMax;  // scaling the objective does not move the optimum

  // Row equilibration and b >= 0. An all-zero row is either vacuous or infeasible.
  std::vector<Index> liveRows;
  for (Index i = 0; i < m; ++i) {
    const double amax = N > 0 ? A.row(i).cwiseAbs().maxCoeff() : 0.0;
    if (amax == 0.0) {
      // Only an equality row can vanish (the others carry a slack or surplus column).
      const double scale = std::abs(b_eq(i)) + A_eq.row(i).cwiseAbs().dot(d.cwiseAbs());
      if (std::abs(b(i)) > kFeasTol * scale) return SolveStatus::kInfeasible;
      continue;
    }
    A.row(i) /= amax;
    b(i) /= amax;
    if (b(i) < 0.0) {
      A.row(i) *= -1.0;
      b(i) = -b(i);
    }
    liveRows.push_back(i);
  }
  const Index mr = static_cast<Index>(liveRows.size());

  // Phase 1 tableau: [A | I | b] with the artificials basic.
  TableauMatrix t0 = TableauMatrix::Zero(mr + 1, N + mr + 1);
  std::vector<Index> basis(static_cast<std::size_t>(mr));
  for (Index i = 0; i < mr; ++i) {
    t0.row(i).head(N) = A.row(liveRows[static_cast<std::size_t>(i)]);
    t0(i, N + i) = 1.0;
    t0(i, N + mr) = b(liveRows[static_cast<std::size_t>(i)]);
    basis[static_cast<std::size_t>(i)] = N + i;
  }
  // Reduced costs of "minimise the sum of artificials" in that basis.
  for (Index i = 0; i < mr; ++i) {
    t0.row(mr).head(N) -= t0.row(i).head(N);
    t0(mr, N + mr) -= t0(i, N + mr);
  }
  Tableau tab(std::move(t0), std::move(basis));
  tab.run(N);  // phase 1 is bounded below by 0
  const double bMax = mr > 0 ? b(liveRows).cwiseAbs().maxCoeff() : 0.0;
  if (-tab.t()(mr, N + mr) > kPhase1Tol * std::max(bMax, 1e-300) * static_cast<double>(mr)) {
    return SolveStatus::kInfeasible;
  }

  // Drive the (zero-valued) artificials out of the basis; a row where that is impossible
  // is a linear combination of the others and is dropped.
  std::vector<Index> keepRows;
  for (Index i = 0; i < mr; ++i) {
    if (tab.basis()[static_cast<std::size_t>(i)] >= N) {
      Index col = -1;
      double best = kPivotTol;
      for (Index j = 0; j < N; ++j) {
        if (std::abs(tab.t()(i, j)) > best) {
          best = std::abs(tab.t()(i, j));
          col = j;
        }
      }
      if (col < 0) continue;
      tab.pivot(i, col);
    }
    keepRows.push_back(i);
  }

  // Phase 2 tableau without artificial columns.
  const Index m2 = static_cast<Index>(keepRows.size());
  TableauMatrix t2(m2 + 1, N + 1);
  std::vector<Index> basis2(static_cast<std::size_t>(m2));
  for (Index i = 0; i < m2; ++i) {
    const Index src = keepRows[static_cast<std::size_t>(i)];
    t2.row(i).head(N) = tab.t().row(src).head(N);
    t2(i, N) = std::max(tab.t()(src, N + mr), 0.0);
    basis2[static_cast<std::size_t>(i)] = tab.basis()[static_cast<std::size_t>(src)];
  }
  t2.row(m2).head(N) = cs.transpose();
  t2(m2, N) = 0.0;
  for (Index i = 0; i < m2; ++i) {
    const double cb = cs(basis2[static_cast<std::size_t>(i)]);
    if (cb != 0.0) t2.row(m2) -= cb * t2.row(i);
  }
  Tableau tab2(std::move(t2), std::move(basis2));
  if (tab2.run(N) == Tableau::Result::kUnbounded) return SolveStatus::kUnbounded;

  VectorXd xs = VectorXd::Zero(N);
  for (Index i = 0; i < m2; ++i) xs(tab2.basis()[static_cast<std::size_t>(i)]) = tab2.t()(i, N);
  x = d + T * xs.head(ns);
  if (objective != nullptr) *objective = c.dot(x);
  return SolveStatus::kOptimal;
}

}  // namespace rbsf
