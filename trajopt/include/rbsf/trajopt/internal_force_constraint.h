#pragma once
/// \file
/// \brief Where three or more contacts stick, their forces are the plant's least-norm ones:
///        no internal force that no actuator steers (docs/model.md: the simulator resolves
///        statically indeterminate forces by least norm).
///
/// The force columns of the sticking contacts, W = [G1_i, T_i], have a null space: force
/// combinations z with W z = 0 that neither the part nor any joint feels. A finger is
/// prismatic along the base's y axis a = R(theta)(0, 1) with its tip at R(theta)(r_i, l_i),
/// so W z = 0 asks of the world forces f_i: f_i . a = 0 (no stroke feels it), sum f_i = 0
/// and sum p_i x f_i = 0 (the part does not; the base's moment is then zero too). With
/// f_i = h_i b along the base's x axis b = R(theta)(1, 0), p_i x b = -l_i, that is
/// sum h_i = 0 and sum h_i l_i = 0: the null space is {h b : h orthogonal to 1 and l}, of
/// dimension (sticking contacts) - 2. For three sticking tips i < j < k it is spanned by
/// h = 1 x l = (l_j - l_k, l_k - l_i, l_i - l_j), the lateral squeeze.
///
/// Least-norm forces are orthogonal to that null space. One row per consecutive triple
/// (i, j, k) of the sticking contacts at knot k (Schedule::forceRole), which together
/// span it:
///
///   g = [ (l_j - l_k) f_i . b + (l_k - l_i) f_j . b + (l_i - l_j) f_k . b ] / (m_o g0) = 0,
///
/// f . b = f_n (-t_y cos(theta - phi) + t_x sin(theta - phi))
///       + f_t ( t_x cos(theta - phi) + t_y sin(theta - phi))
/// with t = t(xi) the boundary tangent in the object frame (n = S t). Units: metres (forces
/// in part weights). Without it the optimiser squeezes three sticking tips as it likes and
/// the plant, which squeezes them by least norm, does not follow.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/trajopt/ad_dynamics.h"
#include "rbsf/trajopt/decision_layout.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief g of one row (file comment) from x = (phi, theta, l_i, l_j, l_k, f_n,i, f_n,j,
///        f_n,k, f_t,i, f_t,j, f_t,k, xi_i, xi_j, xi_k), for any scalar.
template <class S>
S internalForceResidual(const RbsfModel& model, const S* x) {
  using std::cos;
  using std::sin;
  const Cell& cell = model.cell();
  const S c = cos(x[1] - x[0]), s = sin(x[1] - x[0]);  // b in the object frame
  const S h[3] = {x[3] - x[4], x[4] - x[2], x[2] - x[3]};
  S g = S(0.0);
  for (int p = 0; p < 3; ++p) {
    FootPoint<S> foot;
    footPoint(model.shape(), x[11 + p], foot);
    const S fx = x[5 + p] * (-foot.t[1]) + x[8 + p] * foot.t[0];
    const S fy = x[5 + p] * foot.t[0] + x[8 + p] * foot.t[1];
    g += h[p] * (fx * c + fy * s);
  }
  return g / (cell.object.mass * std::max(cell.gravity, 1.0));
}

/// \brief The least-norm rows of the file comment.
class InternalForceConstraint final : public ConstraintSet {
 public:
  /// \brief Variables of one row: phi, theta, then (l, f_n, f_t, xi) of the triple.
  static constexpr int kLocal = 14;

  InternalForceConstraint(const RbsfModel& model, const DecisionLayout& layout,
                          const Schedule& schedule);

  std::string name() const override { return "internal_force"; }
  int rows() const override { return static_cast<int>(rows_.size()); }
  void bounds(VectorRef lower, VectorRef upper) const override;
  void values(const ConstVectorRef& z, VectorRef g) const override;
  const std::vector<std::pair<int, int>>& structure() const override { return structure_; }
  void jacobian(const ConstVectorRef& z, double* values) const override;
  void hessianStructure(HessianPattern& pattern) override;
  void addHessian(const ConstVectorRef& z, const double* lambda, double* values) const override;

 private:
  const RbsfModel& model_;
  std::vector<std::array<int, kLocal>> rows_;  ///< columns of each row's local variables
  std::vector<std::pair<int, int>> structure_;
  std::vector<int> hess_slots_;
};

}  // namespace rbsf::trajopt
