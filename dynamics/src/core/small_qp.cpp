#include "rbsf/dynamics/core/small_qp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rbsf {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A plane rotation G = [c s; -s c] with G (a, b)^T = (h, 0)^T, h = |(a, b)|.
struct Rotation {
  double c = 1.0, s = 0.0, h = 0.0;
};

Rotation rotationZeroing(double a, double b) {
  Rotation g;
  g.h = std::sqrt(a * a + b * b);  // not std::hypot (slow); the entries are far from overflow
  if (g.h > 0.0) {
    g.c = a / g.h;
    g.s = b / g.h;
  }
  return g;
}

/// Columns j and k of M (rows 0..rows-1) become c M_j + s M_k and -s M_j + c M_k: M G^T.
void rotateColumns(QpMatNN& M, int rows, int j, int k, const Rotation& g) {
  double* mj = M.col(j).data();
  double* mk = M.col(k).data();
  for (int i = 0; i < rows; ++i) {
    const double a = mj[i], b = mk[i];
    mj[i] = g.c * a + g.s * b;
    mk[i] = g.c * b - g.s * a;
  }
}

std::string sizeText(long rows, long cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

}  // namespace

const char* toString(QpStatus status) {
  switch (status) {
    case QpStatus::kOptimal:
      return "optimal";
    case QpStatus::kInfeasible:
      return "infeasible";
    case QpStatus::kMaxIterations:
      return "max iterations";
    case QpStatus::kNotConvex:
      return "not convex";
  }
  return "unknown";
}

void SmallQp::resize(int n, int num_equalities, int num_inequalities) {
  if (n < 1 || n > kMaxQpVariables || num_equalities < 0 || num_equalities > kMaxQpEqualities ||
      num_inequalities < 0 || num_inequalities > kMaxQpInequalities) {
    throw std::invalid_argument(
        "SmallQp::resize: n = " + std::to_string(n) + ", " + std::to_string(num_equalities) +
        " equalities, " + std::to_string(num_inequalities) + " inequalities; capacity 1.." +
        std::to_string(kMaxQpVariables) + ", " + std::to_string(kMaxQpEqualities) + ", " +
        std::to_string(kMaxQpInequalities));
  }
  n_ = n;
  me_ = num_equalities;
  mi_ = num_inequalities;
  H.setZero(n, n);
  g.setZero(n);
  A_eq.setZero(me_, n);
  b_eq.setZero(me_);
  A.setZero(mi_, n);
  b.setZero(mi_);
  L_.setZero(n, n);
  J_.setZero(n, n);
  R_.setZero(n, n);
  a_.setZero(n);
  d_.setZero(n);
  z_.setZero(n);
  inv_diag_.setZero(n);
  r_.setZero(n);
  row_norm2_.setZero(mi_);
  tol_fixed_.setZero(mi_);
  tol_scaled_.setZero(mi_);
  slack_.setZero(mi_);
  x.setZero(n);
  y.setZero(me_);
  lambda.setZero(mi_);
  status = QpStatus::kOptimal;
  objective = 0.0;
  num_active = 0;
  iterations = 0;
  infeasible_equality = infeasible_inequality = -1;
  q_ = 0;
  is_active_.fill(false);
}

void SmallQp::checkSizes() const {
  const auto expect = [](const char* name, long rows, long cols, long want_rows, long want_cols) {
    if (rows != want_rows || cols != want_cols) {
      throw std::invalid_argument(std::string("SmallQp: ") + name + " is " + sizeText(rows, cols) +
                                  ", resize() set " + sizeText(want_rows, want_cols));
    }
  };
  expect("H", H.rows(), H.cols(), n_, n_);
  expect("g", g.rows(), g.cols(), n_, 1);
  expect("A_eq", A_eq.rows(), A_eq.cols(), me_, n_);
  expect("b_eq", b_eq.rows(), b_eq.cols(), me_, 1);
  expect("A", A.rows(), A.cols(), mi_, n_);
  expect("b", b.rows(), b.cols(), mi_, 1);
  if (max_iterations < 0) throw std::invalid_argument("SmallQp: max_iterations < 0");
  const auto finiteNonNegative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!finiteNonNegative(feasibility_tolerance) || !finiteNonNegative(dependency_tolerance) ||
      !finiteNonNegative(min_pivot_ratio)) {
    throw std::invalid_argument("SmallQp: tolerances must be finite and non-negative");
  }
}

// H = L L^T from H's lower triangle, then J = L^-T (upper triangular). False if a pivot is
// not above min_pivot_ratio * max_i H_ii (NaN included).
bool SmallQp::factorize() {
  const int n = n_;
  double max_diag = 0.0;
  for (int i = 0; i < n; ++i) max_diag = std::max(max_diag, H(i, i));
  if (!(max_diag > 0.0) || !std::isfinite(max_diag)) return false;
  const double min_pivot = min_pivot_ratio * max_diag;
  // Left-looking, by columns: L(j:n, j) = (H(j:n, j) - sum_k<j L(j:n, k) L(j, k)) / L(j, j).
  for (int j = 0; j < n; ++j) {
    double* lj = L_.col(j).data();
    for (int i = j; i < n; ++i) lj[i] = H(i, j);
    for (int k = 0; k < j; ++k) {
      const double* lk = L_.col(k).data();
      const double ljk = lk[j];
      for (int i = j; i < n; ++i) lj[i] -= lk[i] * ljk;
    }
    if (!(lj[j] > min_pivot)) return false;
    const double ljj = std::sqrt(lj[j]);
    const double inv = 1.0 / ljj;
    lj[j] = ljj;
    inv_diag_[j] = inv;
    for (int i = j + 1; i < n; ++i) lj[i] *= inv;
  }
  // L^T J = I column by column (back substitution; J(i, c) = 0 for i > c).
  for (int c = 0; c < n; ++c) {
    double* jc = J_.col(c).data();
    for (int i = c + 1; i < n; ++i) jc[i] = 0.0;
    jc[c] = inv_diag_[c];
    for (int i = c - 1; i >= 0; --i) {
      const double* li = L_.col(i).data();
      double t = 0.0;
      for (int k = i + 1; k <= c; ++k) t += li[k] * jc[k];
      jc[i] = -t * inv_diag_[i];
    }
  }
  return true;
}

// d = J^T a, z = J2 d2, r = R^-1 d1 for the current active set (q_ rows).
void SmallQp::computeDirections(const QpVecN& a) {
  const int n = n_, q = q_;
  d_norm2_ = d2_norm2_ = 0.0;
  for (int j = 0; j < n; ++j) {
    const double* jj = J_.col(j).data();
    double t = 0.0;
    for (int i = 0; i < n; ++i) t += jj[i] * a[i];
    d_[j] = t;
    d_norm2_ += t * t;
    if (j >= q) d2_norm2_ += t * t;
  }
  for (int i = 0; i < n; ++i) z_[i] = 0.0;
  for (int j = q; j < n; ++j) {
    const double* jj = J_.col(j).data();
    const double dj = d_[j];
    for (int i = 0; i < n; ++i) z_[i] += dj * jj[i];
  }
  for (int i = q - 1; i >= 0; --i) {
    double t = d_[i];
    for (int k = i + 1; k < q; ++k) t -= R_(i, k) * r_[k];
    r_[i] = t / R_(i, i);
  }
}

bool SmallQp::dependent() const {
  return d2_norm2_ <= dependency_tolerance * dependency_tolerance * d_norm2_;
}

// Appends the row of the last computeDirections() to the active set: rotations of J's columns
// q..n-1 turn d2 into (|d2|, 0, ..., 0); R gains the column (d1, |d2|).
void SmallQp::addToActiveSet(int code, double multiplier) {
  const int n = n_, q = q_;
  for (int j = n - 1; j > q; --j) {
    if (d_[j] == 0.0) continue;
    const Rotation rot = rotationZeroing(d_[j - 1], d_[j]);
    d_[j - 1] = rot.h;
    d_[j] = 0.0;
    rotateColumns(J_, n, j - 1, j, rot);
  }
  for (int i = 0; i <= q; ++i) R_(i, q) = d_[i];
  code_[q] = code;
  u_[q] = multiplier;
  q_ = q + 1;
}

// Removes active row `position`: its column leaves R, and rotations of R's rows (and of J's
// columns, alike) restore the triangle.
void SmallQp::dropFromActiveSet(int position) {
  const int n = n_;
  const int q = q_ - 1;  // active rows after the drop
  for (int k = position; k < q; ++k) {
    code_[k] = code_[k + 1];
    u_[k] = u_[k + 1];
    for (int i = 0; i <= k + 1; ++i) R_(i, k) = R_(i, k + 1);
  }
  q_ = q;
  for (int k = position; k < q; ++k) {
    const double sub = R_(k + 1, k);
    if (sub == 0.0) continue;
    const Rotation rot = rotationZeroing(R_(k, k), sub);
    R_(k, k) = rot.h;
    R_(k + 1, k) = 0.0;
    for (int m = k + 1; m < q; ++m) {
      const double a = R_(k, m), b = R_(k + 1, m);
      R_(k, m) = rot.c * a + rot.s * b;
      R_(k + 1, m) = rot.c * b - rot.s * a;
    }
    rotateColumns(J_, n, k, k + 1, rot);
  }
}

// x += t z_; x_scale_ = max(x_scale_, |x|_inf): the largest iterate so far, the scale of x's
// rounding.
void SmallQp::step(double t) {
  double scale = x_scale_;  // a local: stores through x could alias the member
  for (int j = 0; j < n_; ++j) {
    x[j] += t * z_[j];
    scale = std::max(scale, std::abs(x[j]));
  }
  x_scale_ = scale;
}

// slack_ = A x - b over the inactive rows; the inactive row of largest violation per unit
// normal beyond the tolerance (lowest index among ties), or -1.
int SmallQp::mostViolatedRow() {
  const int m = mi_;
  slack_.noalias() = A * x;  // Eigen's GEMV (no temporary: slack_ is a plain vector)
  slack_ -= b;
  // Violation per unit normal: v_i / |a_i| > v_best / |a_best| compared without roots or
  // divisions. A violated zero row (0 >= b_i > 0) wins over every other row.
  int best = -1;
  double best_v2 = 0.0, best_norm2 = 0.0;
  const double scale = x_scale_;
  for (int i = 0; i < m; ++i) {
    if (is_active_[i]) continue;
    const double v = -slack_[i];
    if (!(v > tol_fixed_[i] + tol_scaled_[i] * scale)) continue;
    const double v2 = v * v;
    if (best < 0 || v2 * best_norm2 > best_v2 * row_norm2_[i]) {
      best = i;
      best_v2 = v2;
      best_norm2 = row_norm2_[i];
    }
  }
  return best;
}

QpStatus SmallQp::finish(QpStatus result, int adding_row, double adding_multiplier) {
  y.setZero(me_);
  lambda.setZero(mi_);
  num_active = 0;
  for (int k = 0; k < q_; ++k) {
    if (code_[k] < 0) {
      y[-code_[k] - 1] = u_[k];
    } else {
      lambda[code_[k]] = u_[k];
      active[num_active++] = code_[k];
    }
  }
  if (adding_row >= 0) lambda[adding_row] = adding_multiplier;
  // f(x) = 1/2 |L^T x|^2 + g^T x.
  double quadratic = 0.0, linear = 0.0;
  for (int j = 0; j < n_; ++j) {
    double t = 0.0;
    for (int i = j; i < n_; ++i) t += L_(i, j) * x[i];
    quadratic += t * t;
    linear += g[j] * x[j];
  }
  objective = 0.5 * quadratic + linear;
  status = result;
  return result;
}

// x = -H^-1 g = -J J^T g, the unconstrained minimum; x_scale_ = |x|_inf.
void SmallQp::unconstrainedMinimum() {
  const int n = n_;
  for (int i = 0; i < n; ++i) x[i] = 0.0;
  for (int j = 0; j < n; ++j) {
    const double* jj = J_.col(j).data();
    double t = 0.0;
    for (int i = 0; i <= j; ++i) t += jj[i] * g[i];
    for (int i = 0; i <= j; ++i) x[i] -= t * jj[i];
  }

  double scale = 0.0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(x[i]));
  x_scale_ = scale;
}

// Per inequality row: |a_i|^2 and the two parts of its violation threshold.
void SmallQp::prepareRowTolerances() {
  const int n = n_, mi = mi_;
  for (int i = 0; i < mi; ++i) {
    row_norm2_[i] = 0.0;
    tol_scaled_[i] = 0.0;
  }
  for (int j = 0; j < n; ++j) {
    const double* aj = A.col(j).data();
    for (int i = 0; i < mi; ++i) {
      row_norm2_[i] += aj[i] * aj[i];
      tol_scaled_[i] += std::abs(aj[i]);
    }
  }
  for (int i = 0; i < mi; ++i) {
    tol_scaled_[i] *= feasibility_tolerance;
    tol_fixed_[i] = feasibility_tolerance * std::abs(b[i]);
  }
}

// Equalities: a full step each, of either sign; a dependent row is skipped when consistent
// with the earlier ones. False (after finish()) when one is inconsistent.
bool SmallQp::addEqualities() {
  const int n = n_, me = me_;
  for (int e = 0; e < me; ++e) {
    double residual = b_eq[e], norm1 = 0.0;
    for (int j = 0; j < n; ++j) {
      a_[j] = A_eq(e, j);
      residual -= a_[j] * x[j];
      norm1 += std::abs(a_[j]);
    }
    computeDirections(a_);
    if (dependent()) {
      if (std::abs(residual) <= feasibility_tolerance * (std::abs(b_eq[e]) + norm1 * x_scale_)) {
        continue;  // consistent with the earlier rows: redundant
      }
      infeasible_equality = e;
      finish(QpStatus::kInfeasible, -1, 0.0);
      return false;
    }
    const double t = residual / d2_norm2_;
    step(t);
    for (int k = 0; k < q_; ++k) u_[k] -= t * r_[k];
    addToActiveSet(-e - 1, t);
    ++iterations;
  }
  return true;
}

// Partial (dual) step of computeDirections()'s r: the largest t1 that keeps the active
// inequality multipliers >= 0, and the position of the row that blocks it (-1 and kInf if
// none does).
int SmallQp::blockingRow(double& t1) const {
  t1 = kInf;
  int blocking = -1;
  for (int k = 0; k < q_; ++k) {
    if (code_[k] >= 0 && r_[k] > 0.0) {
      const double ratio = u_[k] / r_[k];
      if (ratio < t1) {
        t1 = ratio;
        blocking = k;
      }
    }
  }
  return blocking;
}

// Adds the violated inequality row p: partial steps, each dropping the blocking row, until
// the full step makes row p hold and it joins the active set. False (after finish()) when
// the solve ends on the way: row p cannot be satisfied, or the iteration limit.
bool SmallQp::addInequality(int p) {
  const int n = n_;
  for (int j = 0; j < n; ++j) a_[j] = A(p, j);
  double s_p = slack_[p];
  double u_plus = 0.0;  // multiplier of row p so far
  for (;;) {
    if (iterations >= max_iterations) {
      finish(QpStatus::kMaxIterations, p, u_plus);
      return false;
    }
    computeDirections(a_);
    double t1 = kInf;
    const int blocking = blockingRow(t1);
    // Full (primal) step: row p holds. After partial steps rounding may leave s_p >= 0.
    const bool no_primal_step = dependent();
    const double t2 = no_primal_step ? kInf : std::max(0.0, -s_p / d2_norm2_);
    if (no_primal_step && blocking < 0) {
      infeasible_inequality = p;
      finish(QpStatus::kInfeasible, p, u_plus);
      return false;
    }
    const double t = std::min(t1, t2);
    if (!no_primal_step) {
      step(t);
    }
    for (int k = 0; k < q_; ++k) {
      u_[k] -= t * r_[k];
      if (code_[k] >= 0 && u_[k] < 0.0) u_[k] = 0.0;  // rounding at the blocking row
    }
    u_plus += t;
    ++iterations;
    if (t2 <= t1) {
      addToActiveSet(p, u_plus);
      is_active_[p] = true;
      return true;
    }
    is_active_[code_[blocking]] = false;
    dropFromActiveSet(blocking);
    s_p = -b[p];
    for (int j = 0; j < n; ++j) s_p += a_[j] * x[j];
  }
}

QpStatus SmallQp::solve() {
  const int n = n_, me = me_, mi = mi_;
  iterations = 0;
  q_ = 0;
  infeasible_equality = infeasible_inequality = -1;
  for (int i = 0; i < mi; ++i) is_active_[i] = false;

  if (!factorize()) {
    x.setZero(n);
    y.setZero(me);
    lambda.setZero(mi);
    num_active = 0;
    objective = std::numeric_limits<double>::quiet_NaN();
    status = QpStatus::kNotConvex;
    return status;
  }

  unconstrainedMinimum();
  prepareRowTolerances();
  if (!addEqualities()) return status;

  // Inequalities: add the most violated row until none is.
  for (;;) {
    const int p = mostViolatedRow();
    if (p < 0) return finish(QpStatus::kOptimal, -1, 0.0);
    if (!addInequality(p)) return status;
  }
}

}  // namespace rbsf
