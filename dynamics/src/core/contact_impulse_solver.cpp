#include "rbsf/dynamics/core/contact_impulse_solver.h"

#include <algorithm>
#include <cmath>

namespace rbsf {
namespace {

// Mode checks accept violations up to this fraction of the problem's scale: the reduced
// systems are solved to ~cond * 1e-16 and the regularised stick blocks have cond ~1e9 / reg.
constexpr double kCheckTol = 1e-9;

// A reduced system whose smallest LU pivot is below this fraction of the largest is treated
// as singular (regularisation pivots are ~regularization = 1e-9 of the largest).
constexpr double kSingularPivot = 1e-6;

constexpr int kMaxLemkeSize = kMaxFingers + kMaxLimitRows + 3 * kMaxFingers;

double sign(double a) { return a > 0.0 ? 1.0 : (a < 0.0 ? -1.0 : 0.0); }

double slideSign(FrictionMode f) {
  return f == FrictionMode::kSlidePositive ? 1.0 : (f == FrictionMode::kSlideNegative ? -1.0 : 0.0);
}

/// LU factorisation with partial pivoting in place (A = P^T L U); false if singular.
bool luFactor(MatII& A, std::array<int, kMaxImpulseRows>& perm, int n) {
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i)
      if (std::abs(A(i, k)) > std::abs(A(p, k))) p = i;
    perm[k] = p;
    if (!(std::abs(A(p, k)) > 0.0)) return false;
    if (p != k) A.row(k).head(n).swap(A.row(p).head(n));
    const double inv = 1.0 / A(k, k);
    for (int i = k + 1; i < n; ++i) {
      const double f = A(i, k) * inv;
      A(i, k) = f;
      if (f == 0.0) continue;
      for (int j = k + 1; j < n; ++j) A(i, j) -= f * A(k, j);
    }
  }
  return true;
}

/// x = A^-1 r from luFactor()'s factors (r is overwritten).
void luSolve(const MatII& LU, const std::array<int, kMaxImpulseRows>& perm, VecI& r, VecI& x,
             int n) {
  // The factorisation swapped whole rows (multipliers included), so every interchange is
  // applied before the forward substitution.
  for (int k = 0; k < n; ++k)
    if (perm[k] != k) std::swap(r[k], r[perm[k]]);
  for (int k = 0; k < n; ++k)
    for (int i = k + 1; i < n; ++i) r[i] -= LU(i, k) * r[k];
  x.resize(n);
  for (int k = n - 1; k >= 0; --k) {
    double s = r[k];
    for (int j = k + 1; j < n; ++j) s -= LU(k, j) * x[j];
    x[k] = s / LU(k, k);
  }
}

}  // namespace

ContactImpulseSolver::ContactImpulseSolver()
    : lemke_(kMaxLemkeSize),
      lcp_M_(Eigen::MatrixXd::Zero(kMaxLemkeSize, kMaxLemkeSize)),
      lcp_q_(Eigen::VectorXd::Zero(kMaxLemkeSize)),
      lcp_z_(Eigen::VectorXd::Zero(kMaxLemkeSize)) {
  resize(0, 0);
}

void ContactImpulseSolver::resize(int nc, int nl) {
  nc_ = nc;
  nl_ = nl;
  regularized_ = false;
  const int n = 2 * nc + nl;
  D.resize(n, n);
  b.resize(n);
  lambda.setZero(n);
  y.resize(n);
}

ImpulseSolvePath ContactImpulseSolver::solve() {
  const int n = numRows();
  iterations = 0;
  pivots = 0;
  if (n == 0) return ImpulseSolvePath::kModeGuess;
  if (!regularized_) {
    eps_ = regularization * D.diagonal().maxCoeff();
    D.diagonal().array() += eps_;
    regularized_ = true;
  }
  for (int it = 0; it < max_mode_iterations; ++it) {
    ++iterations;
    if (!solveModes()) break;
    if (verifyAndUpdateModes()) return ImpulseSolvePath::kModeGuess;
  }
  if (!solveLemke()) return ImpulseSolvePath::kFailed;
  // Lemke solved the regularised LCP directly; re-solving its mode set cleans the
  // null-space component as on the other path (same answer where the problem is regular).
  lemke_lambda_ = lambda;
  lemke_y_ = y;
  const auto lemke_closed = closed;
  const auto lemke_friction = friction;
  if (!solveModes() || !verifyAndUpdateModes()) {
    lambda = lemke_lambda_;
    y = lemke_y_;
    closed = lemke_closed;
    friction = lemke_friction;
  }
  return ImpulseSolvePath::kLemke;
}

bool ContactImpulseSolver::solveModes() {
  const int nu = numUnilateral();
  // Variables (and, aligned with them, equations): lambda_u of closed rows, lambda_t of
  // sticking contacts. A sliding contact's lambda_t = -s mu lambda_n folds into lambda_n's
  // column, which makes the reduced matrix non-symmetric.
  nvar_ = 0;
  for (int u = 0; u < nu; ++u)
    if (closed[u]) var_row_[nvar_++] = u;
  for (int c = 0; c < nc_; ++c)
    if (closed[c] && friction[c] == FrictionMode::kStick) var_row_[nvar_++] = nu + c;
  K_.resize(nvar_, nvar_);
  rhs_.resize(nvar_);
  for (int k = 0; k < nvar_; ++k) {
    const int col = var_row_[k];
    const double slide = col < nc_ ? -slideSign(friction[col]) * mu[col] : 0.0;
    for (int i = 0; i < nvar_; ++i) {
      K_(i, k) = D(var_row_[i], col);
      if (slide != 0.0) K_(i, k) += slide * D(var_row_[i], nu + col);
    }
    rhs_[k] = -b[col];
  }
  // Solve (K + eps I) x = rhs, then x <- (K + eps I)^-1 K x. The rows of m >= 3 sticking
  // contacts are dependent (K singular but for eps), and a right-hand side that is
  // inconsistent by rounding or by the curvature terms (1e-13 m/s, say) would otherwise
  // put rhs_perp / eps ~ 1e-4 N s into the statically indeterminate squeeze of the
  // contacts. The second solve maps that null-space component to zero and leaves the rest
  // (the least-squares, least-norm impulses) unchanged to O(eps). W maps the null space
  // to zero, so the motion is the same either way; only the reported forces and the cone
  // checks see the difference.
  // Only a (nearly) singular K has a null space to clean; it shows as a pivot of order eps.
  K0_ = K_;
  if (!luFactor(K_, perm_, nvar_)) return false;
  luSolve(K_, perm_, rhs_, x_, nvar_);
  double pivot_min = INFINITY, pivot_max = 0.0;
  for (int k = 0; k < nvar_; ++k) {
    pivot_min = std::min(pivot_min, std::abs(K_(k, k)));
    pivot_max = std::max(pivot_max, std::abs(K_(k, k)));
  }
  if (pivot_min < kSingularPivot * pivot_max) {
    for (int k = 0; k < nvar_; ++k) K0_(k, k) -= eps_;
    rhs_.noalias() = K0_ * x_;
    luSolve(K_, perm_, rhs_, x_, nvar_);
  }
  if (!x_.allFinite()) return false;
  lambda.setZero();
  for (int k = 0; k < nvar_; ++k) {
    const int row = var_row_[k];
    lambda[row] = x_[k];
    if (row < nc_ && friction[row] != FrictionMode::kStick)
      lambda[nu + row] = -slideSign(friction[row]) * mu[row] * x_[k];
  }
  y.noalias() = D * lambda;
  y += b;
  return true;
}

bool ContactImpulseSolver::verifyAndUpdateModes() {
  const int nu = numUnilateral();
  const double tol_l = kCheckTol * (1e-12 + lambda.cwiseAbs().maxCoeff());
  const double tol_y = kCheckTol * (1e-12 + b.cwiseAbs().maxCoeff() +
                                    D.cwiseAbs().maxCoeff() * lambda.cwiseAbs().maxCoeff());
  bool ok = true;
  for (int u = 0; u < nu; ++u) {
    if (closed[u] && lambda[u] < -tol_l) {
      closed[u] = false;  // pulling: let it open
      if (u < nc_) friction[u] = FrictionMode::kStick;
      ok = false;
    } else if (!closed[u] && y[u] < -tol_y) {
      closed[u] = true;  // penetrating: close it, sticking first
      if (u < nc_) friction[u] = FrictionMode::kStick;
      ok = false;
    }
  }
  for (int c = 0; c < nc_; ++c) {
    if (!closed[c]) continue;
    const double lt = lambda[nu + c], yt = y[nu + c];
    const double bound = mu[c] * lambda[c];
    if (friction[c] == FrictionMode::kStick) {
      if (std::abs(lt) > bound + tol_l) {
        // Friction cannot hold: slide against the direction the force pushes.
        friction[c] = lt > 0.0 ? FrictionMode::kSlideNegative : FrictionMode::kSlidePositive;
        ok = false;
      }
    } else if (mu[c] > 0.0 && slideSign(friction[c]) * yt < -tol_y) {
      friction[c] = FrictionMode::kStick;  // slip would reverse: try sticking
      ok = false;
    } else if (mu[c] == 0.0) {
      // Without friction the direction only labels the slip.
      friction[c] = yt >= 0.0 ? FrictionMode::kSlidePositive : FrictionMode::kSlideNegative;
    }
  }
  return ok;
}

bool ContactImpulseSolver::solveLemke() {
  const int nu = numUnilateral(), nc = nc_;
  const int N = nu + 3 * nc;
  const int bp = nu, bm = nu + nc, sg = nu + 2 * nc;  // offsets of beta+, beta-, sigma
  auto M = lcp_M_.topLeftCorner(N, N);
  M.setZero();
  const auto Duu = D.topLeftCorner(nu, nu);
  const auto Dut = D.topRightCorner(nu, nc);
  const auto Dtu = D.bottomLeftCorner(nc, nu);
  const auto Dtt = D.bottomRightCorner(nc, nc);
  M.block(0, 0, nu, nu) = Duu;
  M.block(0, bp, nu, nc) = Dut;
  M.block(0, bm, nu, nc) = -Dut;
  M.block(bp, 0, nc, nu) = Dtu;
  M.block(bp, bp, nc, nc) = Dtt;
  M.block(bp, bm, nc, nc) = -Dtt;
  M.block(bm, 0, nc, nu) = -Dtu;
  M.block(bm, bp, nc, nc) = -Dtt;
  M.block(bm, bm, nc, nc) = Dtt;
  for (int c = 0; c < nc; ++c) {
    M(bp + c, sg + c) = 1.0;
    M(bm + c, sg + c) = 1.0;
    M(sg + c, c) = mu[c];
    M(sg + c, bp + c) = -1.0;
    M(sg + c, bm + c) = -1.0;
  }
  auto q = lcp_q_.head(N);
  q.setZero();
  q.head(nu) = b.head(nu);
  q.segment(bp, nc) = b.tail(nc);
  q.segment(bm, nc) = -b.tail(nc);
  const LcpStatus st = solveLcpLemke(M, q, lcp_z_.head(N), lemke_);
  pivots = st.pivots;
  if (!st.solved) {
    lambda.setZero();
    y = b;
    return false;
  }
  lambda.head(nu) = lcp_z_.head(nu);
  lambda.tail(nc) = lcp_z_.segment(bp, nc) - lcp_z_.segment(bm, nc);
  y.noalias() = D * lambda;
  y += b;
  // Modes of the solution, as the next step's guess.
  const double tol_y = kCheckTol * (1e-12 + b.cwiseAbs().maxCoeff());
  for (int u = 0; u < nu; ++u) closed[u] = lambda[u] > 0.0 || y[u] <= tol_y;
  for (int c = 0; c < nc; ++c) {
    const double yt = y[nu + c];
    friction[c] = !closed[c] || std::abs(yt) <= tol_y ? FrictionMode::kStick
                  : sign(yt) > 0.0                    ? FrictionMode::kSlidePositive
                                                      : FrictionMode::kSlideNegative;
  }
  return true;
}

}  // namespace rbsf
