#pragma once
/// \file
/// \brief Lemke's complementary pivoting for general (non-symmetric) linear
///        complementarity problems, allocation-free after construction of its workspace.
///
/// LCP(M, q): find z >= 0 with w = M z + q >= 0 and z^T w = 0.
///
/// Lemke's method augments the problem with an artificial variable z0 and the covering
/// vector d = (1, ..., 1):  w = M z + q + d z0.  Starting from z = 0, z0 = -min(q) (every
/// w >= 0), it follows the almost-complementary path: each pivot brings in the complement
/// of the variable that just left the basis, until z0 leaves (a solution) or the entering
/// column has no positive entry (a secondary ray). Ties in the ratio test are broken
/// lexicographically on the rows of the current basis inverse, which rules out cycling.
///
/// When it terminates: for a copositive-plus M the path ends in a solution whenever the
/// LCP is feasible; the Stewart-Trinkle friction LCP of the simulator (Delassus matrix
/// D >= 0 with friction and slack rows) is covered (Anitescu & Potra 1997), as is every
/// P-matrix. A ray termination proves nothing about other matrices; the caller is told.

#include <Eigen/Core>
#include <vector>

#include "rbsf/dynamics/core/small_solvers.h"

namespace rbsf {

/// \brief Tableau and bookkeeping of solveLcpLemke() for problems of up to `capacity`
///        variables. Construction allocates; solving does not. One per thread.
class LemkeWorkspace {
 public:
  explicit LemkeWorkspace(int capacity);
  int capacity() const { return capacity_; }

 private:
  friend LcpStatus solveLcpLemke(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::VectorXd>& q,
                                 Eigen::Ref<Eigen::VectorXd> z, LemkeWorkspace& ws, int max_pivots);
  int capacity_;
  Eigen::MatrixXd tableau_;  ///< [B^-1 | B^-1 (-M) | B^-1 (-d) | B^-1 q], n x (2n + 2)
  std::vector<int> basis_;   ///< basic variable of each row: w_j = j, z_j = n + j, z0 = 2n
  std::vector<int> ties_;    ///< candidate rows of the ratio test
};

/// \brief Solve LCP(M, q) by Lemke's method (see the file comment). z must have q's size;
///        on success it holds the solution (entries clamped at 0 against rounding) and
///        M z + q >= 0, z^T (M z + q) = 0 hold to rounding.
/// \param max_pivots pivot limit; 0 chooses 50 (n + 1).
/// \return solved = false on a ray termination or at the pivot limit (z is then zero).
/// \throws std::invalid_argument when sizes disagree or exceed the workspace capacity.
LcpStatus solveLcpLemke(const Eigen::Ref<const Eigen::MatrixXd>& M,
                        const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                        LemkeWorkspace& ws, int max_pivots = 0);

}  // namespace rbsf
