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
  const std::vector<Index>& basis() const { return basis_; }

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

namespace {

using ActiveSet = std::array<bool, kMaxFingers>;

/// The principal system A_SS z_S = -p_S of the current active set S and its factors, on
/// fixed-capacity storage (n <= kMaxFingers) so that the pivoting allocates nothing.
struct PrincipalSystem {
  std::array<Index, kMaxFingers> idx{};  // the active indices, in increasing order
  MatCC Ass;
  VecC rhs;
  VecC zs;
  Eigen::LDLT<MatCC> ldlt;
  Eigen::PartialPivLU<MatCC> lu;
};

/// z = the solution of A_SS z_S = -p_S on the active set S, zero off it; by LDLT when A is
/// symmetric, by LU otherwise (see solveLcp()).
void solveOnActiveSet(const MatCC& A, const VecC& p, bool symmetric, const ActiveSet& active,
                      PrincipalSystem& sys, VecC& z) {
  const Index n = p.size();
  Index k = 0;
  for (Index i = 0; i < n; ++i) {
    if (active[static_cast<std::size_t>(i)]) sys.idx[static_cast<std::size_t>(k++)] = i;
  }
  z.setZero();
  if (k == 0) return;
  sys.Ass.resize(k, k);
  sys.rhs.resize(k);
  for (Index a = 0; a < k; ++a) {
    const Index ia = sys.idx[static_cast<std::size_t>(a)];
    sys.rhs(a) = -p(ia);
    for (Index b = 0; b < k; ++b) sys.Ass(a, b) = A(ia, sys.idx[static_cast<std::size_t>(b)]);
  }
  if (symmetric) {
    sys.ldlt.compute(sys.Ass);
    sys.zs = sys.ldlt.solve(sys.rhs);
  } else {
    sys.lu.compute(sys.Ass);
    sys.zs = sys.lu.solve(sys.rhs);
  }
  for (Index a = 0; a < k; ++a) z(sys.idx[static_cast<std::size_t>(a)]) = sys.zs(a);
}

/// Least index whose sign condition fails beyond the tolerance of kLcpTol: z_i < 0 on the
/// active set or w_i < 0 off it; -1 when (z, w) is a solution.
Index firstSignViolation(const ActiveSet& active, const VecC& z, const VecC& w, double aScale,
                         double pScale) {
  const double zMax = z.cwiseAbs().maxCoeff();
  const double zTol = kLcpTol * zMax;
  const double wTol = kLcpTol * (pScale + aScale * zMax);
  for (Index i = 0; i < z.size(); ++i) {
    const bool in = active[static_cast<std::size_t>(i)];
    if ((in && z(i) < -zTol) || (!in && w(i) < -wTol)) return i;
  }
  return -1;
}

/// Makes complementarity exact: w_i = 0 on the active set, z_i = 0 off it, and the other
/// component clamped at 0. The values changed are within the tolerance of the sign tests.
void makeComplementarityExact(const ActiveSet& active, VecC& z, VecC& w) {
  for (Index i = 0; i < z.size(); ++i) {
    if (active[static_cast<std::size_t>(i)]) {
      z(i) = std::max(z(i), 0.0);
      w(i) = 0.0;
    } else {
      z(i) = 0.0;
      w(i) = std::max(w(i), 0.0);
    }
  }
}

}  // namespace

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

  ActiveSet active;
  active.fill(true);
  PrincipalSystem sys;
  // Murty's least-index method visits each of the 2^n principal bases at most once.
  const int limit = (1 << n) + static_cast<int>(n);

  for (;;) {
    solveOnActiveSet(A, p, symmetric, active, sys, z);
    w.noalias() = A * z;
    w += p;
    const Index flip = firstSignViolation(active, z, w, aScale, pScale);
    if (flip < 0) break;
    if (status.pivots >= limit) return status;  // not a P-matrix (or hopelessly conditioned)
    active[static_cast<std::size_t>(flip)] = !active[static_cast<std::size_t>(flip)];
    ++status.pivots;
  }

  makeComplementarityExact(active, z, w);
  status.solved = true;
  return status;
}

// =======================================================================================

namespace {

/// Working state of Lawson-Hanson NNLS on any column-capacity: the work vectors and the
/// passive columns' copy take E's compile-time maximum sizes, so a fixed-capacity E (Mat3C)
/// keeps them on the stack, and MatrixXd on the heap.
template <class MatE, class VecF>
class NnlsSolver {
 public:
  static constexpr int kMaxCols = MatE::MaxColsAtCompileTime;
  using Work = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxCols, 1>;
  using Flags = Eigen::Matrix<Index, Eigen::Dynamic, 1, 0, kMaxCols, 1>;
  using Columns = Eigen::Matrix<double, MatE::RowsAtCompileTime, Eigen::Dynamic, 0,
                                MatE::MaxRowsAtCompileTime, kMaxCols>;

  /// E must have at least one row and one column, and f E.rows() entries.
  NnlsSolver(const MatE& E, const VecF& f)
      : E_(E),
        f_(f),
        m_(E.rows()),
        n_(E.cols()),
        passive_(Flags::Zero(n_)),
        cols_(n_),
        w_(n_),
        z_(n_),
        rejected_(Flags::Zero(n_)) {}

  /// Runs the iteration from x = 0 (x must be zero, of E.cols() entries); `tol` is the
  /// threshold of a positive dual. False if the iteration limit was hit.
  template <class VecX>
  bool run(VecX& x, double tol) {
    // Lawson & Hanson's 3n on the outer iterations (each inner step removes a passive
    // variable, so inner steps never outnumber outer ones), plus slack for rejected trials.
    const long limit = 3 * n_ + 30;
    long iterations = 0;
    for (;;) {
      const Index t = enteringColumn(x, tol);
      if (t < 0) return true;
      if (++iterations > limit) return false;

      passive_(t) = 1;
      solvePassive(z_);
      if (z_(t) <= 0.0) {
        // Rounding made the dual look positive although the column cannot enter with a
        // positive value (L&H ch. 23, the test after step 6): reject it until x changes,
        // otherwise the same column would be chosen forever.
        passive_(t) = 0;
        rejected_(t) = 1;
        continue;
      }
      rejected_.setZero();
      stepBackToPositive(x);
    }
  }

 private:
  /// Step 2/5 of L&H: w = E^T (f - E x), and the active, not rejected column with the most
  /// positive dual above `tol`, or -1.
  template <class VecX>
  Index enteringColumn(const VecX& x, double tol) {
    w_.noalias() = E_.transpose() * (f_ - E_ * x);
    Index t = -1;
    double best = tol;
    for (Index j = 0; j < n_; ++j) {
      if (!passive_(j) && !rejected_(j) && w_(j) > best) {
        best = w_(j);
        t = j;
      }
    }
    return t;
  }

  /// Least squares on the passive columns; returns the full-length solution in `out`.
  void solvePassive(Work& out) {
    Index k = 0;
    for (Index j = 0; j < n_; ++j) {
      if (passive_(j)) cols_(k++) = j;
    }
    Ep_.resize(m_, k);
    for (Index c = 0; c < k; ++c) Ep_.col(c) = E_.col(cols_(c));
    zP_ = Ep_.colPivHouseholderQr().solve(f_);
    out.setZero(n_);
    for (Index c = 0; c < k; ++c) out(cols_(c)) = zP_(c);
  }

  /// Inner loop: step back along x -> z until every passive variable is positive, then
  /// x = z.
  template <class VecX>
  void stepBackToPositive(VecX& x) {
    for (;;) {
      double alpha = kInf;
      Index hit = -1;
      for (Index j = 0; j < n_; ++j) {
        if (passive_(j) && z_(j) <= 0.0) {
          const double a = x(j) / (x(j) - z_(j));
          if (a < alpha) {
            alpha = a;
            hit = j;
          }
        }
      }
      if (hit < 0) {
        x = z_;
        return;
      }
      x += alpha * (z_ - x);
      // The variable that defined alpha leaves the passive set, and so does any other that
      // reached zero up to rounding.
      const double xTol = 10.0 * kEps * x.cwiseAbs().maxCoeff();
      for (Index j = 0; j < n_; ++j) {
        if (passive_(j) && (j == hit || x(j) <= xTol)) {
          passive_(j) = 0;
          x(j) = 0.0;
        }
      }
      solvePassive(z_);
    }
  }

  const MatE& E_;
  const VecF& f_;
  const Index m_;
  const Index n_;
  Flags passive_;
  Flags cols_;
  Work zP_;
  Columns Ep_;
  Work w_;
  Work z_;
  Flags rejected_;
};

/// Lawson-Hanson NNLS on any column-capacity (see NnlsSolver).
template <class MatE, class VecF, class VecX>
bool nnls(const MatE& E, const VecF& f, VecX& x) {
  const Index m = E.rows();
  const Index n = E.cols();
  require(f.size() == m, "solveNnls: f.size() must equal E.rows()");
  x.setZero(n);
  if (n == 0 || m == 0) return true;

  // Scale of the dual vector w = E^T (f - E x): |f - E x| <= |f| throughout, since every
  // iterate improves on x = 0 (the same choice as lsqnonneg, times |f| for scale invariance).
  const double tol = 10.0 * kEps * static_cast<double>(std::max(m, n)) *
                     E.cwiseAbs().colwise().sum().maxCoeff() * f.norm();
  NnlsSolver<MatE, VecF> solver(E, f);
  return solver.run(x, tol);
}

}  // namespace

bool solveNnls(const MatrixXd& E, const VectorXd& f, VectorXd& x) { return nnls(E, f, x); }

bool solveNnls(const Mat3C& E, const Eigen::Vector3d& f, VecC& x) { return nnls(E, f, x); }

// =======================================================================================

namespace {

/// Particular least-norm solution x0 of A_eq x = b_eq (over A_eq's numerical rank; x0 must
/// come in as n zeros) and orthonormal null-space basis Z of A_eq: x = x0 + Z y with x0 in
/// the row space, so |x|^2 = |x0|^2 + |y|^2. Returns how far rounding of b_eq (at
/// rhs_scale) can move x.
double splitEqualities(const MatrixXd& A_eq, const VectorXd& b_eq, Index n, double rhs_scale,
                       VectorXd& x0, MatrixXd& Z) {
  double x_noise = 0.0;
  if (A_eq.rows() > 0 && n > 0) {
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
  return x_noise;
}

/// Normalises the rows of the LDP constraints Gz y >= hz (the feasible set is unchanged) so
/// that hz_i is the signed distance of constraint i from the origin; `keep` lists the rows
/// that are not constant on the affine hull of A_eq x = b_eq.
void normaliseLdpRows(const MatrixXd& G, MatrixXd& Gz, VectorXd& hz, std::vector<Index>& keep) {
  for (Index i = 0; i < G.rows(); ++i) {
    const double nrm = Gz.row(i).norm();
    if (nrm <= kRankTol * G.row(i).norm()) {
      // The row is constant on the affine hull of A_eq x = b_eq: 0 >= hz_i, checked below.
      continue;
    }
    Gz.row(i) /= nrm;
    hz(i) /= nrm;
    keep.push_back(i);
  }
}

/// Largest violation of the kept rows of Gz v >= hz (0 if none is violated).
double worstViolation(const MatrixXd& Gz, const VectorXd& hz, const std::vector<Index>& keep,
                      const VectorXd& v) {
  double viol = 0.0;
  for (Index i : keep) viol = std::max(viol, hz(i) - Gz.row(i).dot(v));
  return viol;
}

/// LDP min |y| s.t. Gz y >= hz over the kept rows, hzMax = max hz_i > 0, through its NNLS
/// dual (Lawson & Hanson ch. 23). False if infeasible.
bool solveLdp(const MatrixXd& Gz, const VectorXd& hz, const std::vector<Index>& keep, double hzMax,
              VectorXd& y) {
  // Scale y so the farthest half-space is at distance 1: the NNLS residual below then
  // has |res|^2 = 1 / (1 + |y|^2), making the infeasibility test scale-free.
  const Index q = static_cast<Index>(keep.size());
  const Index k = Gz.cols();
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
  if (!solveNnls(Eldp, fl, u)) return false;
  const VectorXd res = Eldp * u - fl;
  if (!(res.norm() > 1e-12) || !(res(k) < 0.0)) return false;
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
    if (worstViolation(Gz, hz, keep, ys) <=
        std::max(worstViolation(Gz, hz, keep, y), 1e-14 * hzMax)) {
      y = ys;
    }
  }
  return true;
}

/// The least-norm y with G (x0 + Z y) >= h, each row relaxed by what a movement of the
/// affine set by x_noise can change it; y = 0 when the inequalities already hold at x0.
/// False if infeasible.
bool leastDistanceOnNullSpace(const MatrixXd& G, const VectorXd& h, const VectorXd& x0,
                              const MatrixXd& Z, double x_noise, VectorXd& y) {
  const Index p = G.rows();
  // LDP: min |y| s.t. Gz y >= hz.
  MatrixXd Gz = G * Z;
  VectorXd hz = h - G * x0;
  // Rounding in b_eq moves the affine set by up to x_noise; a cone's apex may then lie
  // just off it. Relax each row by what that movement can change it.
  for (Index i = 0; i < p; ++i) hz(i) -= kFeasTol * G.row(i).norm() * x_noise;
  std::vector<Index> keep;
  normaliseLdpRows(G, Gz, hz, keep);
  const double hzMax = keep.empty() ? 0.0 : hz(keep).maxCoeff();
  if (hzMax > 0.0) return solveLdp(Gz, hz, keep, hzMax, y);
  return true;
}

/// The final check of leastNormInPolyhedron(): x satisfies A_eq x = b_eq and G x >= h to
/// kFeasTol, relative to the terms' size (the rank cut-off and NNLS tolerances must not
/// hide an infeasible answer).
bool verifyFeasible(const MatrixXd& A_eq, const VectorXd& b_eq, const MatrixXd& G,
                    const VectorXd& h, const VectorXd& x, double rhs_scale, double x_noise) {
  if (A_eq.rows() > 0) {
    const double resid = (A_eq * x - b_eq).norm();
    if (!(resid <= kFeasTol * (A_eq.norm() * x.norm() + b_eq.norm() + rhs_scale))) {
      return false;
    }
  }
  for (Index i = 0; i < G.rows(); ++i) {
    const double tol = kFeasTol * (G.row(i).norm() * (x.norm() + x_noise) + std::abs(h(i)));
    if (!(G.row(i).dot(x) >= h(i) - tol)) return false;
  }
  return true;
}

}  // namespace

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
  // How far rounding of b_eq (at rhs_scale) can move x.
  const double x_noise = splitEqualities(A_eq, b_eq, n, rhs_scale, x0, Z);
  if (r > 0) {
    const double resid = (A_eq * x0 - b_eq).norm();
    const double scale = (n > 0 ? A_eq.norm() * x0.norm() : 0.0) + b_eq.norm() + rhs_scale;
    if (!(resid <= kFeasTol * scale)) return SolveStatus::kInfeasible;
  }

  // y = 0 (x = x0) when the inequalities already hold there or there are none.
  VectorXd y = VectorXd::Zero(Z.cols());
  if (p > 0 && Z.cols() > 0 && !leastDistanceOnNullSpace(G, h, x0, Z, x_noise, y)) {
    return SolveStatus::kInfeasible;
  }

  x = x0 + Z * y;
  if (!verifyFeasible(A_eq, b_eq, G, h, x, rhs_scale, x_noise)) return SolveStatus::kInfeasible;
  return SolveStatus::kOptimal;
}

// =======================================================================================

namespace {

/// False if some variable's bounds are crossed or both infinite on the same side (an empty
/// box); throws std::invalid_argument on a NaN bound met before that.
bool boundsConsistent(const VectorXd& lower, const VectorXd& upper) {
  for (Index j = 0; j < lower.size(); ++j) {
    require(!std::isnan(lower(j)) && !std::isnan(upper(j)), "solveLp: NaN bound");
    if (lower(j) > upper(j) || lower(j) == kInf || upper(j) == -kInf) return false;
  }
  return true;
}

/// solveLp()'s problem in standard form: minimise cs^T xs subject to A xs = b, xs >= 0,
/// with x = d + T xs (the first ns columns of xs).
struct StandardLp {
  std::vector<Index> firstCol;  // first column of xs of each variable
  VectorXd d;
  MatrixXd T;
  Index ns = 0;          // structural columns
  Index nBoundRows = 0;  // variables with both bounds finite (a row and a slack each)
  MatrixXd A;            // equality rows, G rows, bound rows
  VectorXd b;
  VectorXd cs;  // cost, scaled to max |cs_j| = 1
};

/// The variable map x = d + T xs, xs >= 0, of the standard form (see solveLp()).
void mapVariables(const VectorXd& lower, const VectorXd& upper, StandardLp& s) {
  const Index n = lower.size();
  s.firstCol.resize(static_cast<std::size_t>(n));
  s.d = VectorXd::Zero(n);
  for (Index j = 0; j < n; ++j) {
    s.firstCol[static_cast<std::size_t>(j)] = s.ns;
    const bool lo = std::isfinite(lower(j));
    const bool up = std::isfinite(upper(j));
    if (lo) {
      s.d(j) = lower(j);
      s.ns += 1;
      if (up) ++s.nBoundRows;
    } else if (up) {
      s.d(j) = upper(j);
      s.ns += 1;
    } else {
      s.ns += 2;
    }
  }
  s.T = MatrixXd::Zero(n, s.ns);
  for (Index j = 0; j < n; ++j) {
    const Index col = s.firstCol[static_cast<std::size_t>(j)];
    if (std::isfinite(lower(j))) {
      s.T(j, col) = 1.0;
    } else if (std::isfinite(upper(j))) {
      s.T(j, col) = -1.0;
    } else {
      s.T(j, col) = 1.0;
      s.T(j, col + 1) = -1.0;
    }
  }
}

/// The rows of the standard form after mapVariables(): A_eq rows, G rows with surplus
/// columns, upper bounds on shifted variables as rows with slacks; and the scaled cost.
void buildRows(const VectorXd& c, const MatrixXd& A_eq, const VectorXd& b_eq, const MatrixXd& G,
               const VectorXd& h, const VectorXd& lower, const VectorXd& upper, StandardLp& s) {
  const Index n = c.size();
  const Index me = A_eq.rows();
  const Index mg = G.rows();
  const Index ns = s.ns;
  const Index m = me + mg + s.nBoundRows;
  const Index N = ns + mg + s.nBoundRows;  // structural + surplus + slack columns
  s.A = MatrixXd::Zero(m, N);
  s.b.resize(m);
  if (me > 0) {
    s.A.block(0, 0, me, ns) = A_eq * s.T;
    s.b.head(me) = b_eq - A_eq * s.d;
  }
  if (mg > 0) {
    s.A.block(me, 0, mg, ns) = G * s.T;
    s.A.block(me, ns, mg, mg) = -MatrixXd::Identity(mg, mg);
    s.b.segment(me, mg) = h - G * s.d;
  }
  Index row = me + mg;
  for (Index j = 0; j < n; ++j) {
    if (std::isfinite(lower(j)) && std::isfinite(upper(j))) {
      s.A(row, s.firstCol[static_cast<std::size_t>(j)]) = 1.0;
      s.A(row, ns + mg + (row - me - mg)) = 1.0;
      s.b(row) = upper(j) - lower(j);
      ++row;
    }
  }
  s.cs = VectorXd::Zero(N);
  s.cs.head(ns) = s.T.transpose() * c;
  const double cMax = N > 0 ? s.cs.cwiseAbs().maxCoeff() : 0.0;
  if (cMax > 0.0) s.cs /= cMax;  // scaling the objective does not move the optimum
}

/// Row equilibration and b >= 0; `liveRows` gets the rows that are not all zero. False if
/// an all-zero row is infeasible (the others are vacuous).
bool equilibrateRows(const MatrixXd& A_eq, const VectorXd& b_eq, StandardLp& s,
                     std::vector<Index>& liveRows) {
  const Index N = s.A.cols();
  for (Index i = 0; i < s.A.rows(); ++i) {
    const double amax = N > 0 ? s.A.row(i).cwiseAbs().maxCoeff() : 0.0;
    if (amax == 0.0) {
      // Only an equality row can vanish (the others carry a slack or surplus column).
      const double scale = std::abs(b_eq(i)) + A_eq.row(i).cwiseAbs().dot(s.d.cwiseAbs());
      if (std::abs(s.b(i)) > kFeasTol * scale) return false;
      continue;
    }
    s.A.row(i) /= amax;
    s.b(i) /= amax;
    if (s.b(i) < 0.0) {
      s.A.row(i) *= -1.0;
      s.b(i) = -s.b(i);
    }
    liveRows.push_back(i);
  }
  return true;
}

/// Phase 1 tableau [A | I | b] over the live rows, with the artificials basic and the
/// reduced costs of "minimise the sum of artificials" in that basis.
Tableau phaseOneTableau(const StandardLp& s, const std::vector<Index>& liveRows) {
  const Index N = s.A.cols();
  const Index mr = static_cast<Index>(liveRows.size());
  TableauMatrix t0 = TableauMatrix::Zero(mr + 1, N + mr + 1);
  std::vector<Index> basis(static_cast<std::size_t>(mr));
  for (Index i = 0; i < mr; ++i) {
    t0.row(i).head(N) = s.A.row(liveRows[static_cast<std::size_t>(i)]);
    t0(i, N + i) = 1.0;
    t0(i, N + mr) = s.b(liveRows[static_cast<std::size_t>(i)]);
    basis[static_cast<std::size_t>(i)] = N + i;
  }
  for (Index i = 0; i < mr; ++i) {
    t0.row(mr).head(N) -= t0.row(i).head(N);
    t0(mr, N + mr) -= t0(i, N + mr);
  }
  return Tableau(std::move(t0), std::move(basis));
}

/// Drives the (zero-valued) artificials, columns N and up, out of the basis of the phase 1
/// tableau; a row where that is impossible is a linear combination of the others and is
/// dropped. Returns the rows kept.
std::vector<Index> driveOutArtificials(Tableau& tab, Index N) {
  std::vector<Index> keepRows;
  for (Index i = 0; i < tab.rows(); ++i) {
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
  return keepRows;
}

/// Phase 2 tableau: the kept rows of the phase 1 tableau `tab` without the artificial
/// columns, and the reduced costs of cs in their basis.
Tableau phaseTwoTableau(const Tableau& tab, const std::vector<Index>& keepRows,
                        const VectorXd& cs) {
  const Index N = cs.size();
  const Index mr = tab.rows();
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
  return Tableau(std::move(t2), std::move(basis2));
}

}  // namespace

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
  if (!boundsConsistent(lower, upper)) return SolveStatus::kInfeasible;

  // Standard form: x = d + T xs with xs >= 0. Finite lower bound: shift; only an upper
  // bound: reflect; free: split into xs+ - xs-. Upper bounds on shifted variables become
  // rows with slacks; G rows get surplus variables.
  StandardLp s;
  mapVariables(lower, upper, s);
  buildRows(c, A_eq, b_eq, G, h, lower, upper, s);
  std::vector<Index> liveRows;
  if (!equilibrateRows(A_eq, b_eq, s, liveRows)) return SolveStatus::kInfeasible;
  const Index N = s.A.cols();
  const Index mr = static_cast<Index>(liveRows.size());

  Tableau tab = phaseOneTableau(s, liveRows);
  tab.run(N);  // phase 1 is bounded below by 0
  const double bMax = mr > 0 ? s.b(liveRows).cwiseAbs().maxCoeff() : 0.0;
  if (-tab.t()(mr, N + mr) > kPhase1Tol * std::max(bMax, 1e-300) * static_cast<double>(mr)) {
    return SolveStatus::kInfeasible;
  }
  const std::vector<Index> keepRows = driveOutArtificials(tab, N);

  Tableau tab2 = phaseTwoTableau(tab, keepRows, s.cs);
  if (tab2.run(N) == Tableau::Result::kUnbounded) return SolveStatus::kUnbounded;

  const Index m2 = static_cast<Index>(keepRows.size());
  VectorXd xs = VectorXd::Zero(N);
  for (Index i = 0; i < m2; ++i) xs(tab2.basis()[static_cast<std::size_t>(i)]) = tab2.t()(i, N);
  x = s.d + s.T * xs.head(s.ns);
  if (objective != nullptr) *objective = c.dot(x);
  return SolveStatus::kOptimal;
}

}  // namespace rbsf
