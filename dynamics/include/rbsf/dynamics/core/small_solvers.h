#pragma once
/// \file
/// \brief Exact small dense solvers for the contact problems of the model: the LCP of
///        eqs. 21-24, non-negative least squares, least-distance programming and linear
///        programming. Sizes are a few dozen at most; every method terminates finitely
///        and returns an exact (to rounding) answer, never a sampled one.

#include <Eigen/Core>

#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief Outcome of solveLcp().
struct LcpStatus {
  bool solved = false;  ///< false only if the pivot limit was reached (A not a P-matrix)
  int pivots = 0;       ///< number of principal pivots performed
};

/// \brief LCP(A, p): find z >= 0 with w = A z + p >= 0 and z^T w = 0 (eqs. 21-22), by
///        Murty's least-index principal pivoting, started from the all-active set (every
///        contact closed), which is the usual answer. Finite and exact when A is a
///        P-matrix (A = G1^T M^-1 G1 with G1 of full column rank is positive definite).
///        Allocation-free for n <= kMaxFingers. On return z >= 0, w >= 0 and z_i w_i = 0
///        hold exactly; w = A z + p to rounding. Throws std::invalid_argument if A is not
///        n x n.
LcpStatus solveLcp(const MatCC& A, const VecC& p, VecC& z, VecC& w);

/// \brief Lawson-Hanson NNLS: minimise |E x - f| subject to x >= 0. Exact active set.
/// \return false if the iteration limit was hit. Throws std::invalid_argument if
///         f.size() != E.rows().
bool solveNnls(const Eigen::MatrixXd& E, const Eigen::VectorXd& f, Eigen::VectorXd& x);

/// \brief The same for three equations on up to kMaxFingers unknowns (a part's force and
///        moment balance over its contacts), allocation-free.
bool solveNnls(const Mat3C& E, const Eigen::Vector3d& f, VecC& x);

/// \brief Result of leastNormInPolyhedron() and solveLp().
enum class SolveStatus { kOptimal, kInfeasible, kUnbounded };

/// \brief Least-norm point of a polyhedron: minimise |x|^2 subject to A_eq x = b_eq and
///        G x >= h. Reduces to least-distance programming on the null space of A_eq and
///        solves that through NNLS (Lawson & Hanson, ch. 23). A_eq may have dependent rows
///        (consistent ones are accepted; an inconsistent system is infeasible). Either
///        matrix may have zero rows. `rhs_scale` is the magnitude of the terms b_eq was
///        computed from: when they nearly cancel, b_eq's rounding error is relative to
///        them, not to |b_eq|, and the consistency test must know it. Never kUnbounded; kInfeasible
///        is also returned in the (not observed) case that the inner NNLS hits its iteration limit.
///        Throws std::invalid_argument on inconsistent sizes.
SolveStatus leastNormInPolyhedron(const Eigen::MatrixXd& A_eq, const Eigen::VectorXd& b_eq,
                                  const Eigen::MatrixXd& G, const Eigen::VectorXd& h,
                                  Eigen::VectorXd& x, double rhs_scale = 0.0);

/// \brief Linear program: minimise c^T x subject to A_eq x = b_eq, G x >= h and
///        lower <= x <= upper (entries may be +-infinity). Dense two-phase simplex with
///        Bland's rule (no cycling). On kOptimal, x holds an optimal vertex. Throws
///        std::invalid_argument on inconsistent sizes or NaN bounds, std::runtime_error if
///        the simplex iteration guard trips (only possible through rounding trouble).
SolveStatus solveLp(const Eigen::VectorXd& c, const Eigen::MatrixXd& A_eq,
                    const Eigen::VectorXd& b_eq, const Eigen::MatrixXd& G, const Eigen::VectorXd& h,
                    const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd& x,
                    double* objective = nullptr);

}  // namespace rbsf
