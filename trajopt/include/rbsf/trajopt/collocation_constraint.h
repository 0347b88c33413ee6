#pragma once
/// \file
/// \brief Trapezoidal collocation of the dynamics M(q) dv/dt = r(q, v, tau, f, xi)
///        (MODEL.md "Dynamics", eqs. 5, 6, 18, 19) on every interval.

#include <vector>

#include "rbsf/dynamics/model.h"
#include "rbsf/trajopt/ad_dynamics.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief For interval k of run j (h = T_j / N_j; hbar_j = planned T_j / N_j, a constant
///        that only scales the rows), 2 (m + 4) rows, all = 0:
///   D_q = (q_{k+1} - q_k - h/2 (v_k + v_{k+1})) / hbar                          [m, rad]
///   D_v = (1/2 (M(q_k) + M(q_{k+1})) (v_{k+1} - v_k) - h/2 (r_k + r_{k+1})) / (hbar W_o)
///   (D_v in units of the object's weight W_o = m_o max(g0, 1 m/s^2) [N, N m per N]: rows
///   of order one, so a tolerance or a derivative check means the same on every row)
/// with r_e = u(tau_e) + sum_i [G_i f_i ; -J_i^T f_i] - Q(q_e, v_e) at knots e = k, k+1 and
/// f_i = f_n,k,i n_i(xi_e,i) + f_t,k,i t_i(xi_e,i) in the world frame (knotRhs in
/// ad_dynamics.h): the forces of knot k are held over the interval (decision_layout.h).
/// (Multiplied by h rather than divided, so T_j enters linearly.)
///
/// Jacobian: forward-mode AutoDiff over the interval's two knot blocks and T_j. Its
/// structure is the set of entries that are non-zero at a generic (random) point: the
/// same for every interval, found once in the constructor.
///
/// Hessian of lambda^T (D_q; D_v), exact: per knot, -h/(2 hbar) times the Hessian of
/// lambda_v^T r (each contact's wrench by nested AutoDiff over (phi, theta, l_i of that
/// knot, f_n, f_t of knot k, xi of that knot); the bias Q in closed form); the mass-matrix
/// term through M_theta,theta's sum m_i L_i^2; and the T_j row -1/(2 N_j hbar) (lambda_q
/// on v, grad lambda_v^T r over both knots' variables).
class CollocationConstraint final : public ConstraintSet {
 public:
  CollocationConstraint(const RbsfModel& model, const DecisionLayout& layout,
                        const Schedule& schedule);

  std::string name() const override { return "collocation"; }
  int rows() const override { return 2 * n_ * layout_.intervals(); }
  void bounds(VectorRef lower, VectorRef upper) const override;
  void values(const ConstVectorRef& z, VectorRef g) const override;
  const std::vector<std::pair<int, int>>& structure() const override { return structure_; }
  void jacobian(const ConstVectorRef& z, double* values) const override;
  void hessianStructure(HessianPattern& pattern) override;
  void addHessian(const ConstVectorRef& z, const double* lambda, double* values) const override;

  /// \brief The 2 (m + 4) defects of interval k from its local vector
  ///        (knot k block, knot k+1 block, T_j).
  template <class S>
  void defect(const S* local, int k, ConfigVector<S>& out) const;

 private:
  int localSize() const { return 2 * layout_.knotSize() + 1; }
  void gather(const ConstVectorRef& z, int k, double* local) const;
  /// \brief Accumulate the Hessian of lambda_v^T r at knot kk (k or k + 1) of interval k,
  ///        with the forces of knot k, scaled by `scale` into slots starting at *slot; grad
  ///        (over knots k and k + 1) accumulates the gradient of lambda_v^T r.
  void knotHessian(const ConstVectorRef& z, int k, int kk, const double* lambda_v, double scale,
                   const int*& slot, double* values, Eigen::VectorXd& grad) const;
  std::vector<int> intervalVariables(int k) const;  ///< T_j's partners on interval k

  const RbsfModel& model_;
  DecisionLayout layout_;
  const Schedule& schedule_;
  int n_;
  std::vector<double> hbar_;                        ///< per run [s]
  double inv_weight_;                               ///< 1 / W_o [1/N]
  std::vector<std::pair<int, int>> local_pattern_;  ///< (row, local column)
  std::vector<std::pair<int, int>> structure_;
  std::vector<int> hess_slots_;
  mutable std::vector<ADScalar> local_ad_;  ///< jacobian() workspace
};

template <class S>
void CollocationConstraint::defect(const S* local, int k, ConfigVector<S>& out) const {
  const int ks = layout_.knotSize();
  const int j = schedule_.run_of_interval[k];
  const double inv_hbar = 1.0 / hbar_[j];
  const S h = local[2 * ks] / static_cast<double>(schedule_.runs[j].intervals);
  ConfigVector<S> r0, r1, dv(n_), Mdv0, Mdv1;
  knotRhs<S>(model_, layout_, local, 0, r0);
  knotRhs<S>(model_, layout_, local, ks, r1, 0);
  const int ov = layout_.localV();
  for (int a = 0; a < n_; ++a) dv[a] = local[ks + ov + a] - local[ov + a];
  massTimes<S>(model_.cell(), local, 0, dv, Mdv0);
  massTimes<S>(model_.cell(), local, ks, dv, Mdv1);
  out.resize(2 * n_);
  for (int a = 0; a < n_; ++a) {
    out[a] = (local[ks + a] - local[a] - 0.5 * h * (local[ov + a] + local[ks + ov + a])) * inv_hbar;
    out[n_ + a] =
        (0.5 * (Mdv0[a] + Mdv1[a]) - 0.5 * h * (r0[a] + r1[a])) * (inv_hbar * inv_weight_);
  }
}

}  // namespace rbsf::trajopt
