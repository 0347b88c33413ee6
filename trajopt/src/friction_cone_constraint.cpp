#include "rbsf/trajopt/friction_cone_constraint.h"

#include <algorithm>

namespace rbsf::trajopt {

FrictionConeConstraint::FrictionConeConstraint(const DecisionLayout& layout,
                                               const Schedule& schedule, double mu_s,
                                               double margin) {
  for (int k = 0; k < layout.knots(); ++k)
    for (int i = 0; i < layout.fingers(); ++i)
      if (schedule.forceRole(k, i) == ContactRole::kStick) {
        const bool relied = schedule.runOf(std::min(k, layout.intervals() - 1)).relied[i];
        knots_.push_back({layout.fn(k) + i, layout.ft(k) + i, (relied ? margin : 1.0) * mu_s});
      }
  for (int r = 0; r < rows(); ++r) {
    structure_.emplace_back(r, knots_[r / 2].fn);
    structure_.emplace_back(r, knots_[r / 2].ft);
  }
}

void FrictionConeConstraint::bounds(VectorRef lower, VectorRef upper) const {
  lower.setConstant(-kInfinity);
  upper.setZero();
}

void FrictionConeConstraint::values(const ConstVectorRef& z, VectorRef g) const {
  for (std::size_t c = 0; c < knots_.size(); ++c) {
    const double fn = z[knots_[c].fn], ft = z[knots_[c].ft], mu = knots_[c].mu;
    g[2 * c] = ft - mu * fn;
    g[2 * c + 1] = -ft - mu * fn;
  }
}

void FrictionConeConstraint::jacobian(const ConstVectorRef&, double* values) const {
  for (std::size_t c = 0; c < knots_.size(); ++c) {
    values[4 * c + 0] = -knots_[c].mu;
    values[4 * c + 1] = 1.0;
    values[4 * c + 2] = -knots_[c].mu;
    values[4 * c + 3] = -1.0;
  }
}

}  // namespace rbsf::trajopt
