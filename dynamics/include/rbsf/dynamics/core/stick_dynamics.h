#pragma once
/// \file
/// \brief Acceleration-level dynamics with sticking contacts: phase C (every contact
///        sticks, paper 2.2 and eq. 7) and phase P (one contact sticks, the others slide
///        frictionlessly). Analysis code: these allocate, unlike forwardDynamicsU().

#include <Eigen/Core>

#include "rbsf/dynamics/core/model.h"

namespace rbsf {

/// \brief Friction cones as linear inequalities G lambda >= 0 on lambda = [F_n; F_t]
///        (m normal then m tangential components): per contact f_n >= 0,
///        mu f_n - f_t >= 0 and mu f_n + f_t >= 0 (the two edges of eq. 7). 3m x 2m.
Eigen::MatrixXd frictionConeRows(int m, double mu);

/// \brief Result of solvePhaseC() or solvePhaseP().
struct StickSolution {
  bool feasible = false;  ///< forces found inside every friction cone, F_n >= 0
  Eigen::VectorXd fn;     ///< normal forces per contact [N]
  Eigen::VectorXd ft;     ///< tangential forces per contact, along t_i [N]
  Eigen::VectorXd vdot;   ///< accelerations dv/dt, order of q
  int pivot = -1;         ///< phase P: the sticking contact
};

/// \brief Phase C: every contact sticks (normal and tangential relative accelerations
///        zero), so the object moves with the base (omega_o = theta'). With N = [G1 T],
///        K = N^T M^-1 N and r = [h_n; h_t] + N^T M^-1 (u - Q) the forces satisfy
///        K lambda = -r, a consistent system of rank m + 2 (statically indeterminate for
///        m >= 3). The rule: among all solutions, the least-norm lambda inside the
///        friction cones |f_t| <= mu_s f_n (eq. 7). Infeasible when no solution fits the
///        cones; then fn/ft hold the least-norm solution regardless of the cones.
///        Accelerations are unique: dv/dt = M^-1 (u - Q + N lambda).
/// \pre model.updateContacts(q, data) has been called for q.
StickSolution solvePhaseC(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau,
                          ModelData& data);

/// \brief Phase P: contact `pivot` sticks (its normal and tangential relative
///        accelerations vanish), every other contact is frictionless and may open (LCP
///        on the Schur complement). Feasible when the pivot's force lies in its cone.
/// \pre model.updateContacts(q, data) has been called for q.
StickSolution solvePhaseP(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau,
                          int pivot, ModelData& data);

}  // namespace rbsf
