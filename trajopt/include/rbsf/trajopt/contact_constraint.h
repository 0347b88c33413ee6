#pragma once
/// \file
/// \brief Where each fingertip is relative to the object boundary, at every knot.

#include "rbsf/dynamics/core/model.h"
#include "rbsf/trajopt/ad_dynamics.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief For knot k and finger i, with e_i = p_i(q) - (x_o + R(phi) c(xi_i)) [m]
///        (p_i = R(theta)(r_i, l_i), docs/model.md eqs. 1-2), two rows:
///   t_i . e_i = 0     xi_i is the foot point of the tip (closest boundary point);
///   n_i . e_i = 0     when the contact is on (stick or slide) in a run touching the knot,
///   n_i . e_i <= 0    otherwise (n_i inward: the tip stays outside, no penetration).
/// t_i = R(phi) t(xi_i), n_i = S t_i. Row order: knot-major, then finger, then (t, n).
/// Knot 0 has only the t rows: q_0 = plan.q0 is fixed, so n . e there would constrain
/// nothing but xi_0 (along which it is stationary at the foot point): a zero row.
/// Jacobian by AutoDiff over (x, y, phi, theta, l_i, xi_i): a dense 2 x 6 block; Hessian
/// of lambda_t (t . e) + lambda_n (n . e) by nested AutoDiff over the same six.
class ContactConstraint final : public ConstraintSet {
 public:
  ContactConstraint(const RbsfModel& model, const DecisionLayout& layout, const Schedule& schedule);

  std::string name() const override { return "contact"; }
  int rows() const override { return 2 * m_ * layout_.knots() - m_; }
  void bounds(VectorRef lower, VectorRef upper) const override;
  void values(const ConstVectorRef& z, VectorRef g) const override;
  const std::vector<std::pair<int, int>>& structure() const override { return structure_; }
  void jacobian(const ConstVectorRef& z, double* values) const override;
  void hessianStructure(HessianPattern& pattern) override;
  void addHessian(const ConstVectorRef& z, const double* lambda, double* values) const override;

  /// \brief (t . e, n . e) of finger i from its local vector (x, y, phi, theta, l_i, xi_i).
  template <class S>
  void residual(int i, const S* local, S& te, S& ne) const;

 private:
  void columns(int k, int i, int* cols) const;
  /// \brief Row of (t . e) of finger i at knot k; (n . e) follows it when k > 0.
  int row(int k, int i) const { return k == 0 ? i : m_ + 2 * ((k - 1) * m_ + i); }
  int rowsAt(int k) const { return k == 0 ? 1 : 2; }

  const RbsfModel& model_;
  DecisionLayout layout_;
  const Schedule& schedule_;
  int m_;
  std::vector<std::pair<int, int>> structure_;
  std::vector<int> hess_slots_;
};

template <class S>
void ContactConstraint::residual(int i, const S* local, S& te, S& ne) const {
  using std::cos;
  using std::sin;
  const S cp = cos(local[2]), sp = sin(local[2]);
  const S ct = cos(local[3]), st = sin(local[3]);
  FootPoint<S> foot;
  footPoint(model_.shape(), local[5], foot);
  const double r = model_.cell().fingers[i].r;
  const Vec2T<S> c_w = rotated<S>(cp, sp, foot.c);
  const Vec2T<S> t_w = rotated<S>(cp, sp, foot.t);
  const S ex = ct * r - st * local[4] - local[0] - c_w[0];
  const S ey = st * r + ct * local[4] - local[1] - c_w[1];
  te = t_w[0] * ex + t_w[1] * ey;
  ne = -t_w[1] * ex + t_w[0] * ey;  // n = S t = (-t_y, t_x)
}

}  // namespace rbsf::trajopt
