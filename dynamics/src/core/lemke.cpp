#include "rbsf/dynamics/core/lemke.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace rbsf {
namespace {

// A tableau entry counts as positive in the ratio test above this fraction of the largest
// magnitude in M (pivoting on rounding noise would blow the tableau up).
constexpr double kPivotTol = 1e-12;
// Ratios equal within this relative tolerance are ties, broken lexicographically.
constexpr double kTieTol = 1e-12;

// Columns of the tableau: w_0..w_{n-1} | z_0..z_{n-1} | z0 | rhs. The w block starts as the
// identity and then always holds B^-1, which the lexicographic rule reads.
void buildTableau(const Eigen::Ref<const Eigen::MatrixXd>& M,
                  const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::MatrixXd& T,
                  std::vector<int>& basis) {
  const int n = static_cast<int>(q.size());
  const int c_z0 = 2 * n, c_rhs = 2 * n + 1;
  T.topLeftCorner(n, n).setIdentity();
  T.block(0, n, n, n) = -M;
  T.col(c_z0).head(n).setConstant(-1.0);
  T.col(c_rhs).head(n) = q;
  for (int i = 0; i < n; ++i) basis[i] = i;
}

// Pivot on (r, c) over the n rows and the 2n + 2 columns in use.
void pivot(Eigen::MatrixXd& T, int n, int r, int c) {
  const int c_rhs = 2 * n + 1;
  const double p = T(r, c);
  T.row(r).head(c_rhs + 1) /= p;
  for (int i = 0; i < n; ++i) {
    if (i == r) continue;
    const double f = T(i, c);
    if (f != 0.0) T.row(i).head(c_rhs + 1) -= f * T.row(r).head(c_rhs + 1);
  }
}

// Keeps the rows of least ratio, ties within kTieTol: row i's `ratio` against the `count`
// rows in `ties`, whose ratio is `best`. Writes ties[count] at most, so `ties` may be the
// list being scanned.
void keepMinimum(double ratio, int i, double& best, int& count, std::vector<int>& ties) {
  if (count == 0 || ratio < best - kTieTol * (1.0 + std::abs(best))) {
    best = ratio;
    count = 0;
    ties[count++] = i;
  } else if (ratio <= best + kTieTol * (1.0 + std::abs(best))) {
    ties[count++] = i;
  }
}

// Ratio test of the entering column: the rows of minimum rhs / pivot (ties within kTieTol)
// among those with a pivot above piv_tol go to `ties`; returns their count (0: a ray).
int minimumRatioRows(const Eigen::MatrixXd& T, int n, int entering, double piv_tol,
                     std::vector<int>& ties) {
  const int c_rhs = 2 * n + 1;
  int count = 0;
  double best = 0.0;
  for (int i = 0; i < n; ++i) {
    const double a = T(i, entering);
    if (!(a > piv_tol)) continue;
    keepMinimum(T(i, c_rhs) / a, i, best, count, ties);
  }
  return count;
}

// The leaving row among the `count` tied rows: the one of z0 if tied (it leaves: done next),
// else lexicographic on the B^-1 rows / pivot. Overwrites `ties`.
int leavingRow(const Eigen::MatrixXd& T, int n, int entering, const std::vector<int>& basis,
               std::vector<int>& ties, int count) {
  const int c_z0 = 2 * n;
  int row = -1;
  for (int k = 0; k < count; ++k)
    if (basis[ties[k]] == c_z0) row = ties[k];
  for (int col = 0; row < 0 && col < n; ++col) {
    int kept = 0;
    double lex = 0.0;
    for (int k = 0; k < count; ++k) {
      const int i = ties[k];
      keepMinimum(T(i, col) / T(i, entering), i, lex, kept, ties);
    }
    count = kept;
    if (count == 1) row = ties[0];
  }
  if (row < 0) row = ties[0];  // rows of B^-1 are independent: only rounding gets here
  return row;
}

// z from the basic z_j of the final tableau (clamped at 0 against rounding), zero elsewhere.
void readSolution(const Eigen::MatrixXd& T, int n, const std::vector<int>& basis,
                  Eigen::Ref<Eigen::VectorXd> z) {
  const int c_rhs = 2 * n + 1;
  for (int i = 0; i < n; ++i) {
    const int b = basis[i];
    if (b >= n && b < 2 * n) z[b - n] = std::max(0.0, T(i, c_rhs));
  }
}

}  // namespace

LemkeWorkspace::LemkeWorkspace(int capacity)
    : capacity_(capacity),
      tableau_(Eigen::MatrixXd::Zero(capacity, 2 * capacity + 2)),
      basis_(static_cast<size_t>(capacity)),
      ties_(static_cast<size_t>(capacity)) {}

LcpStatus solveLcpLemke(const Eigen::Ref<const Eigen::MatrixXd>& M,
                        const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                        LemkeWorkspace& ws, int max_pivots) {
  const int n = static_cast<int>(q.size());
  if (M.rows() != n || M.cols() != n || z.size() != n)
    throw std::invalid_argument("solveLcpLemke: M must be n x n and z of size n");
  if (n > ws.capacity_) throw std::invalid_argument("solveLcpLemke: problem exceeds workspace");
  LcpStatus status;
  z.setZero();
  if (n == 0 || q.minCoeff() >= 0.0) {
    status.solved = true;
    return status;
  }
  if (max_pivots <= 0) max_pivots = 50 * (n + 1);

  Eigen::MatrixXd& T = ws.tableau_;
  const int c_z0 = 2 * n;
  buildTableau(M, q, T, ws.basis_);
  const double piv_tol = kPivotTol * std::max(1.0, M.cwiseAbs().maxCoeff());

  // First pivot: z0 enters at the most negative q_i, making every basic variable >= 0.
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (q[i] < q[r]) r = i;
  pivot(T, n, r, c_z0);
  ++status.pivots;
  int leaving = ws.basis_[r];
  ws.basis_[r] = c_z0;

  while (status.pivots < max_pivots) {
    const int entering = leaving < n ? leaving + n : leaving - n;  // the complement
    // Minimum-ratio rows, then lexicographic on (rhs, B^-1 row) / pivot.
    const int count = minimumRatioRows(T, n, entering, piv_tol, ws.ties_);
    if (count == 0) return LcpStatus{false, status.pivots};  // secondary ray
    const int row = leavingRow(T, n, entering, ws.basis_, ws.ties_, count);
    pivot(T, n, row, entering);
    ++status.pivots;
    leaving = ws.basis_[row];
    ws.basis_[row] = entering;
    if (leaving == c_z0) {
      readSolution(T, n, ws.basis_, z);
      status.solved = true;
      return status;
    }
  }
  z.setZero();
  return LcpStatus{false, status.pivots};
}

}  // namespace rbsf
