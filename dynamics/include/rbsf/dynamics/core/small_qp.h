#pragma once
/// \file
/// \brief A dense, fixed-capacity, allocation-free solver of small strictly convex quadratic
///        programs (the Goldfarb-Idnani dual active-set method), for control laws that solve
///        one QP every period.
///
/// Problem. With x in R^n,
///   minimise    f(x) = 1/2 x^T H x + g^T x
///   subject to  A_eq x  = b_eq     (me rows, possibly none)
///               A x    >= b        (mi rows, possibly none)
/// with H symmetric positive definite, n <= kMaxQpVariables, me <= kMaxQpEqualities and
/// mi <= kMaxQpInequalities. Only the lower triangle of H is read. Rows of A_eq may be linearly
/// dependent (consistent dependent rows are skipped); rows of A may be anything, including
/// duplicated, redundant and zero rows. The data must be finite: a NaN in H's lower triangle is
/// reported as kNotConvex, but NaN or infinite entries elsewhere give meaningless answers (a NaN
/// row is never seen as violated).
///
/// Optimality (KKT) conditions of the answer, with multipliers y (equalities) and lambda
/// (inequalities):
///   H x + g - A_eq^T y - A^T lambda = 0,   A_eq x = b_eq,   A x >= b,
///   lambda >= 0,   lambda_i (A x - b)_i = 0.
///
/// Method. Goldfarb & Idnani, "A numerically stable dual method for solving strictly convex
/// quadratic programs", Math. Programming 27 (1983) 1-33; the structure of Turlach's QuadProg
/// (Fortran, the R package quadprog). The method starts at the unconstrained minimum -H^-1 g (a
/// dual feasible point) and adds violated constraints one at a time, keeping every iterate the
/// minimiser of f over the active constraints held with equality, with non-negative inequality
/// multipliers:
///   - H = L L^T (Cholesky); J = L^-T Q and R come from the QR factorisation
///     L^-1 N = Q [R; 0] of the active constraints' normals N (J^T H J = I). The first q
///     columns J1 of J span H^-1 N (H^-1 N = J1 R), the others J2 the directions that keep
///     every active row's value (N^T J2 = 0). Initially q = 0 and J = L^-T.
///   - Equalities are added first, each with a full (possibly negative) step.
///   - Then, while some inactive inequality row is violated, the most violated one p (largest
///     violation divided by the row's Euclidean norm; the lowest index among ties) is added:
///     with d = J^T a_p, the primal direction is z = J2 d2 and the dual direction
///     r = R^-1 d1. With s_p = a_p^T x - b_p < 0, the full step t2 = -s_p / (z^T a_p) makes
///     row p hold (z^T a_p = |d2|^2);
///     the partial step t1 = min u_k / r_k over the active inequality rows with r_k > 0 keeps
///     their multipliers u non-negative. When t1 < t2, x moves by t1 z and the blocking row
///     is dropped; otherwise x moves by t2 z and p joins the active set. When z = 0 (a_p lies
///     in the span of the active normals) only the multipliers move (and a row is dropped);
///     when moreover no r_k > 0, the problem is infeasible.
///   - Adding a row turns d2 into (+-|d2|, 0, ..., 0) by Givens rotations of J's columns
///     q..n-1 (R gains the column (d1, +-|d2|)); dropping a row removes its column
///     from R and restores the triangle by Givens rotations of R's rows and J's columns.
/// In exact arithmetic the objective increases strictly with every full step and the method
/// ends after finitely many steps (no cycling, no anti-cycling rule needed).
///
/// Tolerances (all relative, so that the solver does not depend on the problem's units):
///   - Cholesky pivots must exceed min_pivot_ratio * max_i H_ii (default 1e-12), otherwise
///     kNotConvex. A smaller pivot means cond(H) > 1e12: numerically H is not positive
///     definite, and steps along its flattest directions would carry few correct digits.
///   - An inequality row counts as violated when b_i - a_i^T x exceeds
///     feasibility_tolerance * (|b_i| + |a_i|_1 X) (default 1e-10), X the largest |x|_inf of
///     the iterates so far (the unconstrained minimum included). The bracket bounds the
///     rounding error of the residual, and that of x, which is relative to the largest iterate
///     it was computed from; the margin of ~1e6 over double precision covers the drift of the
///     active rows through the steps (measured on random problems: worst violations 1e-13,
///     1e-12 and 2e-11 of the bracket or less for cond(H) = 1, 1e3, 1e6), so that rounding noise
///     does not re-add rows. Consistent dependent equalities are skipped by the same test. Rows of
///     the active set are never re-tested.
///   - a_p counts as dependent on the active normals (z = 0) when |d2| <=
///     dependency_tolerance * |d| (default 1e-10): |d2| / |d| is the sine of the angle, in the
///     metric of H^-1, between a_p and the span of the active normals. This bounds R's
///     condition number (about 1 / dependency_tolerance), hence the multipliers' accuracy.
///     Rows closer to dependence than that are treated as dependent: a feasible set reached
///     only through such a row (whose full step |s_p| / |d2|^2 would be huge) may be reported
///     infeasible.
///
/// Output. On kOptimal, x is the minimiser, `objective` is f(x) (computed as
/// 1/2 |L^T x|^2 + g^T x, from the factor actually used), y and lambda are the multipliers
/// (lambda is zero off the active set, and lambda >= 0 exactly), `active` lists the inequality
/// rows of the final active set. Accuracy: active rows hold to rounding, inactive rows hold to
/// feasibility_tolerance (relative, as above), stationarity to about eps * cond(H) relative to
/// its terms (measured worst cases 1e-15, 3e-14 and 5e-12 for cond(H) = 1, 1e3, 1e6).
///
/// Infeasibility and the iteration limit. Every iterate (x, y, lambda) is (in exact
/// arithmetic) the minimiser of f over the points that hold the active rows and, while a row p
/// is being added, the row p at its current value a_p^T x; stationarity
/// H x + g = A_eq^T y + A^T lambda holds with lambda >= 0, lambda_p being the multiplier
/// accumulated so far by the row being added (p is not listed in `active`). When solve()
/// returns kInfeasible or kMaxIterations, x, y, lambda and `active` hold that last iterate: x
/// satisfies the equalities added so far and the active inequality rows (to rounding), and may
/// violate the others.
///   - kInfeasible: infeasible_equality names an equality row dependent on the earlier ones
///     but inconsistent with them (x then minimises f subject to the earlier equalities), or
///     infeasible_inequality names the row p that no step could satisfy: a_p is a combination
///     of the active normals with non-positive weights on the inequality rows, so every point
///     that holds the active rows has a_p^T x at most its current, violating value.
///   - kMaxIterations: `objective` is a lower bound of the optimal value (weak duality:
///     f(x) <= the dual function at (y, lambda) <= f(x*)). max_iterations bounds all steps,
///     but the me equality rows are always added (at most kMaxQpEqualities steps) before it
///     is checked.
///   - kNotConvex: x and the multipliers are zero and `objective` is NaN.
/// Near the boundary the verdict follows the tolerances: constraints inconsistent by less than
/// feasibility_tolerance are reported optimal (the violation within the tolerance), and a
/// feasible set that only a nearly dependent row (below dependency_tolerance) would reach is
/// reported infeasible.
///
/// Complexity. Cholesky n^3/3 and J = L^-T n^3/6 flops; each step O(n (mi + n)): the
/// residuals of the inactive rows (n mi), d = J^T a_p and z (n^2 each), r (q^2 / 2), the
/// Givens rotations of an addition ((n - q) n) or of a drop ((q - l) (n + q)). Typical
/// problems take about as many steps as there are active rows at the solution. No heap
/// memory: every array has its capacity fixed at compile time (about 28 kB per SmallQp, 12 kB
/// of it A), and solve() neither allocates nor throws. Deterministic: the same inputs give
/// the same bits.
///
/// Use: resize(n, me, mi) once (throws std::invalid_argument beyond capacity), fill H, g,
/// A_eq, b_eq, A, b, then call solve() every period. solve() trusts the sizes set by
/// resize(); checkSizes() (not on the hot path) throws std::invalid_argument if the caller
/// has since resized one of the public problem matrices inconsistently.

#include <array>
#include <cstdint>
#include <limits>

#include <Eigen/Core>

namespace rbsf {

/// \brief Largest number of variables n of a SmallQp.
inline constexpr int kMaxQpVariables = 16;
/// \brief Largest number of equality rows of a SmallQp.
inline constexpr int kMaxQpEqualities = 16;
/// \brief Largest number of inequality rows of a SmallQp.
inline constexpr int kMaxQpInequalities = 112;

/// \brief n-vector (x, g).
using QpVecN = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxQpVariables, 1>;
/// \brief n x n matrix (H).
using QpMatNN =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxQpVariables, kMaxQpVariables>;
/// \brief me-vector (b_eq, y).
using QpVecE = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxQpEqualities, 1>;
/// \brief me x n matrix (A_eq).
using QpMatEN =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxQpEqualities, kMaxQpVariables>;
/// \brief mi-vector (b, lambda).
using QpVecI = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxQpInequalities, 1>;
/// \brief mi x n matrix (A).
using QpMatIN =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxQpInequalities, kMaxQpVariables>;

/// \brief Outcome of SmallQp::solve().
enum class QpStatus : std::uint8_t {
  kOptimal,        ///< x is the minimiser; y, lambda its multipliers
  kInfeasible,     ///< the constraints cannot all hold; x is the last iterate (see the file)
  kMaxIterations,  ///< max_iterations steps were taken; x is the last iterate
  kNotConvex,      ///< the Cholesky factorisation of H failed (H not positive definite)
};

/// \brief "optimal", "infeasible", "max iterations", "not convex".
const char* toString(QpStatus status);

/// \brief A strictly convex QP of fixed capacity and its Goldfarb-Idnani solution (see the
///        file's comment). resize(), fill the public problem members, solve().
class SmallQp {
 public:
  SmallQp() { resize(1, 0, 0); }
  SmallQp(int n, int num_equalities, int num_inequalities) {
    resize(n, num_equalities, num_inequalities);
  }

  /// \brief Sets the sizes and zeroes the problem and the solution. Throws
  ///        std::invalid_argument unless 1 <= n <= kMaxQpVariables,
  ///        0 <= num_equalities <= kMaxQpEqualities and
  ///        0 <= num_inequalities <= kMaxQpInequalities.
  void resize(int n, int num_equalities, int num_inequalities);
  int numVariables() const { return n_; }
  int numEqualities() const { return me_; }
  int numInequalities() const { return mi_; }

  /// \brief Throws std::invalid_argument if a public problem matrix no longer has the size
  ///        set by resize(), or a tolerance or the iteration limit is out of range. Not
  ///        needed on the hot path; solve() reads the sizes of resize() without checking.
  void checkSizes() const;

  // Problem (inputs). solve() does not modify them.
  QpMatNN H;     ///< n x n, symmetric positive definite; only the lower triangle is read
  QpVecN g;      ///< n
  QpMatEN A_eq;  ///< me x n
  QpVecE b_eq;   ///< me
  QpMatIN A;     ///< mi x n: A x >= b
  QpVecI b;      ///< mi

  // Settings.
  int max_iterations =
      1000;  ///< steps (additions + drops) after the equalities' before kMaxIterations
  double feasibility_tolerance = 1e-10;  ///< relative violation accepted (see the file)
  double dependency_tolerance = 1e-10;   ///< |d2| / |d| below which a row is dependent
  double min_pivot_ratio = 1e-12;        ///< Cholesky pivot / max H_ii below which kNotConvex

  /// \brief Solves the QP. Never allocates, never throws.
  QpStatus solve();

  // Solution (outputs of the last solve()).
  QpStatus status = QpStatus::kOptimal;
  QpVecN x;                ///< the minimiser (or the last iterate, see the file)
  double objective = 0.0;  ///< f(x)
  QpVecE y;                ///< equality multipliers (zero for a skipped dependent row)
  QpVecI lambda;           ///< inequality multipliers, >= 0, zero off the active set
  std::array<int, kMaxQpVariables> active{};  ///< inequality rows of the active set
  int num_active = 0;                         ///< entries of `active` in use
  int iterations = 0;  ///< steps taken: rows added (equalities included) plus rows dropped
  int infeasible_equality = -1;    ///< on kInfeasible: the inconsistent equality row, or -1
  int infeasible_inequality = -1;  ///< on kInfeasible: the row that could not be added, or -1

 private:
  bool factorize();
  /// \brief x = -H^-1 g, the unconstrained minimum, and x_scale_ = |x|_inf.
  void unconstrainedMinimum();
  /// \brief |a_i|^2 and the two parts of the violation threshold of every inequality row.
  void prepareRowTolerances();
  /// \brief Adds the equality rows; false (status set by finish()) if one is inconsistent.
  bool addEqualities();
  /// \brief Adds the violated inequality row p, dropping blocking rows on the way; false
  ///        (status set by finish()) if the solve ended: p infeasible or iteration limit.
  bool addInequality(int p);
  /// \brief The active position whose multiplier limits the partial step, -1 if none;
  ///        t1 gets that step (kInf if none).
  int blockingRow(double& t1) const;
  void computeDirections(const QpVecN& a);
  bool dependent() const;
  void addToActiveSet(int code, double multiplier);
  void dropFromActiveSet(int position);
  void step(double t);
  int mostViolatedRow();
  QpStatus finish(QpStatus result, int adding_row, double adding_multiplier);

  int n_ = 0, me_ = 0, mi_ = 0;
  QpMatNN L_;  // Cholesky factor of H (lower triangle)
  QpMatNN J_;  // L^-T Q
  QpMatNN R_;  // upper triangular q x q
  int q_ = 0;  // active rows
  // Active rows in order: code >= 0 is inequality row `code`, code < 0 equality -code - 1.
  std::array<int, kMaxQpVariables> code_{};
  std::array<double, kMaxQpVariables> u_{};  // their multipliers
  std::array<bool, kMaxQpInequalities> is_active_{};
  QpVecN a_, d_, z_, r_;                   // the row being added, J^T a, primal and dual directions
  double d_norm2_ = 0.0, d2_norm2_ = 0.0;  // |d|^2 and |d2|^2 of computeDirections()
  double x_scale_ = 0.0;                   // largest |x|_inf of the iterates so far
  QpVecN inv_diag_;                        // 1 / L_jj
  QpVecI row_norm2_, slack_;               // |a_i|^2, A x - b
  QpVecI tol_fixed_, tol_scaled_;          // tol |b_i|, tol |a_i|_1: violated beyond the
                                           // first plus x_scale_ times the second
};

}  // namespace rbsf
