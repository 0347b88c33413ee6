#include "rbsf/trajopt/friction_cone_constraint.h"

namespace rbsf::trajopt {

FrictionConeConstraint::FrictionConeConstraint(const DecisionLayout& layout,
                                               const Schedule& schedule, double mu_s, double margin)
    : mu_(margin * mu_s) {
  for (int k = 0; k < layout.knots(); ++k)
    for (int i = 0; i < layout.fingers(); ++i)
      if (schedule.forceRole(k, i) == ContactRole::kStick)
        knots_.emplace_back(layout.fn(k) + i, layout.ft(k) + i);
  for (int r = 0; r < rows(); ++r) {
    structure_.emplace_back(r, knots_[r / 2].first);
    structure_.emplace_back(r, knots_[r / 2].second);
  }
}

void FrictionConeConstraint::bounds(VectorRef lower, VectorRef upper) const {
  lower.setConstant(-kInfinity);
  upper.setZero();
}

void FrictionConeConstraint::values(const ConstVectorRef& z, VectorRef g) const {
  for (std::size_t c = 0; c < knots_.size(); ++c) {
    const double fn = z[knots_[c].first], ft = z[knots_[c].second];
    g[2 * c] = ft - mu_ * fn;
    g[2 * c + 1] = -ft - mu_ * fn;
  }
}

void FrictionConeConstraint::jacobian(const ConstVectorRef&, double* values) const {
  for (std::size_t c = 0; c < knots_.size(); ++c) {
    values[4 * c + 0] = -mu_;
    values[4 * c + 1] = 1.0;
    values[4 * c + 2] = -mu_;
    values[4 * c + 3] = -1.0;
  }
}

}  // namespace rbsf::trajopt
