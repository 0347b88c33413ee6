#pragma once
/// \file
/// \brief Velocity-Verlet collocation of the dynamics M(q) dv/dt = r(q, v, tau, f, xi)
///        (docs/model.md "Dynamics", eqs. 5, 6, 18, 19) on every interval.

#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/trajopt/ad_dynamics.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief Velocity-Verlet collocation, for interval k of run j (h = T_j / N_j; hbar_j =
///        planned T_j / N_j, a constant that only scales the rows), 2 (m + 4) rows, all = 0:
///   D_q = (M(q_k) (q_{k+1} - q_k - h v_k) - h^2/2 r_k) / (hbar^2 W_o)
///   D_v = (1/2 (M(q_k) + M(q_{k+1})) (v_{k+1} - v_k) - h/2 (r_k + r_{k+1})) / (hbar W_o)
/// i.e. q_{k+1} = q_k + h v_k + h^2/2 a_k and v_{k+1} = v_k + h/2 (a_k + a_{k+1}) with
/// a = M^-1 r, written without the inverse; both rows in units of the object's weight
/// W_o = m_o max(g0, 1 m/s^2) [N per N]: rows of order one, so a tolerance or a
/// derivative check means the same on every row. r_e = u(tau_e) + sum_i [G_i f_i ;
/// -J_i^T f_i] - Q(q_e, v_e) at knots e = k, k+1 with that knot's own forces f_i =
/// f_n,e,i n_i(xi_e,i) + f_t,e,i t_i(xi_e,i) in the world frame (knotRhs in ad_dynamics.h).
///
/// Why this scheme and not the trapezoidal rule (q_{k+1} - q_k = h/2 (v_k + v_{k+1})):
/// eliminating v gives q_{k+1} - 2 q_k + q_{k-1} = h^2 a_k on equal steps, so every knot's
/// force is seen by the positions, as in SHAKE/RATTLE. Under the trapezoidal rule (with
/// forces per knot or held per interval) the positions see only the mean of neighbouring
/// forces: forces alternating from knot to knot, with velocities alternating to match,
/// leave every position and contact constraint unchanged. Solutions used that freedom:
/// the held tangential force of a pivot alternated +52 / -46 / +66 N where the contact
/// problem at the knots gives 5-12 N, so cones were checked on forces the simulator never
/// applies.
///
/// Jacobian: forward-mode AutoDiff over the interval's two knot blocks and T_j. Its
/// structure is the set of entries that are non-zero at a generic (random) point: the
/// same for every interval, found once in the constructor.
///
/// Hessian of lambda_q^T D_q + lambda_v^T D_v, exact: per knot e, the Hessian of
/// mu_e^T r_e times -h/2 with mu_k = c_v lambda_v + h c_q lambda_q, mu_k+1 = c_v lambda_v
/// (c_q = 1 / (hbar^2 W_o), c_v = 1 / (hbar W_o); each contact's wrench by nested AutoDiff
/// over (phi, theta, l_i, f_n, f_t, xi of that knot); the bias Q in closed form); the
/// mass-matrix terms through M_theta,theta's sum m_i L_i^2; and the T_j row and column:
/// d/dT of -h/2 mu_e^T r_e and of D_q's -h M(q_k) v_k, d^2/dT^2 = -c_q / N_j^2 lambda_q^T r_k.
/// A knot's wrenches enter the two intervals that share it; their Hessian is linear in the
/// multiplier, so it is differentiated once per knot with the two intervals' -h/2 mu summed
/// (the nested AutoDiff is most of the Hessian's cost), and its gradient kept for the T_j
/// columns. Workspace is sized in hessianStructure(); addHessian() allocates nothing.
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
  /// \brief Interval k's step and row scales (class comment).
  struct IntervalScales {
    int N;      ///< intervals of its run j
    double h;   ///< T_j / N_j [s]
    double cq;  ///< 1 / (hbar_j^2 W_o), D_q's scale
    double cv;  ///< 1 / (hbar_j W_o), D_v's scale
  };
  /// \brief Interval k's scales and the multipliers of its knots' r: mu0 (knot k, in D_q
  ///        and D_v), mu1 (knot k + 1, D_v only) and nu0 = d(h mu0)/dh (the T_j column's
  ///        multiplier of knot k's r; knot k + 1's is mu1).
  IntervalScales intervalMultipliers(const ConstVectorRef& z, const double* lambda, int k,
                                     double* mu0, double* nu0, double* mu1) const;
  /// \brief The columns of z that finger i's contact wrench at knot kk depends on:
  ///        (phi, theta, l_i, f_n,i, f_t,i, xi_i), the AD6x2 seeds' order.
  void wrenchColumns(int kk, int i, int* cols) const;
  /// \brief Write the Hessian of knot_mu_^T (the contact wrenches of knot kk) into slots from
  ///        *slot and keep the wrenches' gradients in wrench_grad_.
  void contactHessian(const ConstVectorRef& z, int kk, const int*& slot, double* values) const;
  /// \brief Accumulate `scale` times the Hessian of mu^T (u - Q) at knot kk (k or k + 1) of
  ///        interval k into slots from *slot; grad (over knots k and k + 1) accumulates the
  ///        gradient of nu^T r_kk (the T_j column's multiplier), wrenches included.
  void knotHessian(const ConstVectorRef& z, int k, int kk, const double* mu, const double* nu,
                   double scale, const int*& slot, double* values, double* grad) const;

  const RbsfModel& model_;
  DecisionLayout layout_;
  const Schedule& schedule_;
  int n_;
  std::vector<double> hbar_;                        ///< per run [s]
  double inv_weight_;                               ///< 1 / W_o [1/N]
  std::vector<std::pair<int, int>> local_pattern_;  ///< (row, local column)
  std::vector<std::pair<int, int>> structure_;
  std::vector<int> hess_slots_;
  /// \brief T_j's partners on an interval, as offsets from knot k: every variable of the
  ///        two knots that r or D_q touch, i.e. all but the positions x and y.
  std::vector<int> interval_cols_;
  mutable std::vector<ADScalar> local_ad_;  ///< jacobian() workspace
  mutable std::vector<double> knot_mu_;     ///< addHessian(): summed -h/2 mu per knot, K x n
  /// \brief addHessian(): d w_b / d c6_a of each knot's contacts, K x m x 5 x 6.
  mutable std::vector<double> wrench_grad_;
};

template <class S>
void CollocationConstraint::defect(const S* local, int k, ConfigVector<S>& out) const {
  const int ks = layout_.knotSize();
  const int j = schedule_.run_of_interval[k];
  const double inv_hbar = 1.0 / hbar_[j];
  const S h = local[2 * ks] / static_cast<double>(schedule_.runs[j].intervals);
  ConfigVector<S> r0, r1, dq(n_), dv(n_), Mdq, Mdv0, Mdv1;
  knotRhs<S>(model_, layout_, local, 0, r0);
  knotRhs<S>(model_, layout_, local, ks, r1);
  const int ov = layout_.localV();
  for (int a = 0; a < n_; ++a) {
    dq[a] = local[ks + a] - local[a] - h * local[ov + a];
    dv[a] = local[ks + ov + a] - local[ov + a];
  }
  massTimes<S>(model_.cell(), local, 0, dq, Mdq);
  massTimes<S>(model_.cell(), local, 0, dv, Mdv0);
  massTimes<S>(model_.cell(), local, ks, dv, Mdv1);
  out.resize(2 * n_);
  for (int a = 0; a < n_; ++a) {
    out[a] = (Mdq[a] - 0.5 * h * h * r0[a]) * (inv_hbar * inv_hbar * inv_weight_);
    out[n_ + a] =
        (0.5 * (Mdv0[a] + Mdv1[a]) - 0.5 * h * (r0[a] + r1[a])) * (inv_hbar * inv_weight_);
  }
}

}  // namespace rbsf::trajopt
