#pragma once
/// \file
/// \brief The velocity-level contact problem of one time step (Stewart & Trinkle 1996,
///        Anitescu & Potra 1997) with planar Coulomb friction, solved exactly.
///
/// Rows. The caller stacks nu = nc + nl unilateral rows (the normal rows of nc contacts,
/// then nl frictionless rows such as the mechanism's hard limits) and the nc tangential
/// rows of the contacts, in this order:
///   row r < nc          normal of contact r          impulse lambda_n,r >= 0
///   nc <= row < nu      unilateral limit row         impulse lambda_l >= 0
///   row nu + r          tangent of contact r         impulse lambda_t,r
/// With the Delassus matrix D = W^T M^-1 W (W the constraint columns, see simulator.h)
/// and b = W^T v_free + stabilisation terms, the rows' velocities after the step are
///   y = D lambda + b        [m/s or rad/s].
///
/// Conditions (exact 2-D Coulomb: the planar friction cone has two edges):
///   unilateral rows:  0 <= lambda_u  _|_  y_u >= 0
///   contact r:        |lambda_t| <= mu_r lambda_n;  y_t = 0 when |lambda_t| < mu_r lambda_n;
///                     lambda_t = -mu_r lambda_n sign(y_t) when y_t != 0 (slip).
/// As an LCP (Stewart-Trinkle; lambda_t = beta+ - beta-, sigma the slip magnitude):
///   z = (lambda_u, beta+, beta-, sigma),
///   w_u     = D_uu lambda_u + D_ut (beta+ - beta-) + b_u
///   w_beta+ = D_tu lambda_u + D_tt (beta+ - beta-) + b_t + sigma
///   w_beta- = -(D_tu lambda_u + D_tt (beta+ - beta-) + b_t) + sigma
///   w_sigma = mu lambda_n - beta+ - beta-,        0 <= z _|_ w >= 0.
///
/// Method. Each row is given a mode (unilateral: open / closed; contact: stick, slide in
/// the +t or -t direction). A mode set turns the conditions into a square linear system:
/// closed rows y_u = 0, sticking rows y_t = 0, sliding impulses lambda_t = -s mu lambda_n.
/// Starting from the caller's guess (usually last step's modes), the system is solved and
/// verified; violated rows change mode (primal-dual active set) for a few iterations.
/// When that does not settle, Lemke's method solves the LCP above. Both paths return an
/// exact solution of the same conditions; the guess only decides the speed and, where the
/// solution is not unique, which solution.
///
/// Regularisation. Sticking contacts of a rigid part on m >= 3 fingers make D singular
/// (rank m + 2 for 2m contact rows, paper 2.2), so the forces are statically indeterminate.
/// The solver works with D + eps I, eps = regularization * max diag(D): a constraint-force
/// mixing term that picks (to O(eps)) the least-norm impulses among the indeterminate ones
/// and changes the rows' velocities by eps lambda, far below every tolerance. A reduced
/// system K x = r is solved as x1 = (K + eps I)^-1 r, x = (K + eps I)^-1 K x1: the second
/// solve removes the component rhs_perp / eps that a right-hand side inconsistent by
/// rounding (or by the curvature terms) would put into the null space, so the impulses are
/// the least-squares least-norm ones, not merely the regularised ones.

#include <array>
#include <cstdint>

#include "rbsf/dynamics/core/lemke.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief Most unilateral limit rows: both ends of theta and of every stroke.
inline constexpr int kMaxLimitRows = 2 * (kMaxFingers + 1);
/// \brief Most rows of the step's contact problem.
inline constexpr int kMaxImpulseRows = 2 * kMaxFingers + kMaxLimitRows;

using VecI = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxImpulseRows, 1>;
using MatII =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxImpulseRows, kMaxImpulseRows>;

/// \brief Mode of a contact's friction row.
enum class FrictionMode : std::uint8_t {
  kStick,          ///< y_t = 0, |lambda_t| <= mu lambda_n
  kSlidePositive,  ///< y_t >= 0, lambda_t = -mu lambda_n
  kSlideNegative,  ///< y_t <= 0, lambda_t = +mu lambda_n
};

/// \brief Which path produced the last solution.
enum class ImpulseSolvePath : std::uint8_t {
  kModeGuess,  ///< the guessed or iterated mode set verified
  kLemke,      ///< Lemke's method
  kFailed,     ///< Lemke stopped on a ray or its pivot limit (lambda = 0)
};

/// \brief The contact problem of one step and its solution. The caller sets the sizes with
///        resize(), then fills D, b, mu and the mode guess, and calls solve(). Capacity is
///        fixed at construction; nothing allocates afterwards.
class ContactImpulseSolver {
 public:
  ContactImpulseSolver();

  /// \brief nc contacts (each a normal and a tangential row), nl limit rows.
  void resize(int nc, int nl);
  int numContacts() const { return nc_; }
  int numUnilateral() const { return nc_ + nl_; }
  int numRows() const { return 2 * nc_ + nl_; }

  // Problem (inputs).
  MatII D;  ///< Delassus matrix, rows ordered as above; solve() adds eps to its diagonal
  VecI b;   ///< free row velocities + stabilisation
  std::array<double, kMaxFingers> mu{};                    ///< friction coefficient per contact
  std::array<bool, kMaxFingers + kMaxLimitRows> closed{};  ///< unilateral modes (guess/result)
  std::array<FrictionMode, kMaxFingers> friction{};        ///< friction modes (guess/result)
  double regularization = 1e-9;                            ///< eps / max diag(D)
  int max_mode_iterations = 8;                             ///< mode updates before Lemke

  /// \brief Solve; on return lambda, y, closed and friction hold the solution. The first
  ///        call after resize() regularises D in place; later calls (a re-solve with other
  ///        mu, the modes of the previous solution as the guess) reuse it.
  ImpulseSolvePath solve();

  // Solution (outputs).
  VecI lambda;         ///< impulses [N s] (or [N m s] on a base-angle limit row)
  VecI y;              ///< row velocities after the step, D_eps lambda + b
  int iterations = 0;  ///< mode-set solves of the last call
  int pivots = 0;      ///< Lemke pivots of the last call

 private:
  bool solveModes();
  bool verifyAndUpdateModes();
  bool solveLemke();

  int nc_ = 0, nl_ = 0;
  bool regularized_ = false;
  double eps_ = 0.0;
  MatII K_, K0_;  // reduced system of the mode set: LU factors of K + eps I, and K
  std::array<int, kMaxImpulseRows> perm_{};
  VecI rhs_, x_, lemke_lambda_, lemke_y_;
  std::array<int, kMaxImpulseRows> var_row_{};  // full row of each reduced variable
  int nvar_ = 0;
  LemkeWorkspace lemke_;
  Eigen::MatrixXd lcp_M_;
  Eigen::VectorXd lcp_q_, lcp_z_;
};

}  // namespace rbsf
