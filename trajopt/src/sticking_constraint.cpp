#include "rbsf/trajopt/sticking_constraint.h"

namespace rbsf::trajopt {

StickingConstraint::StickingConstraint(const DecisionLayout& layout, const Schedule& schedule,
                                       bool keep_slide_direction) {
  for (int k = 0; k < layout.intervals(); ++k)
    for (int i = 0; i < layout.fingers(); ++i) {
      const ContactRole role = schedule.role(k, i);
      const int dir = schedule.runOf(k).slide_direction[i];
      if (role == ContactRole::kStick)
        rows_.push_back({layout.xi(k) + i, layout.xi(k + 1) + i, 0});
      else if (role == ContactRole::kSlide && keep_slide_direction && dir != 0)
        rows_.push_back({layout.xi(k) + i, layout.xi(k + 1) + i, dir});
    }
  for (int r = 0; r < rows(); ++r) {
    structure_.emplace_back(r, rows_[r].from);
    structure_.emplace_back(r, rows_[r].to);
  }
}

void StickingConstraint::bounds(VectorRef lower, VectorRef upper) const {
  for (int r = 0; r < rows(); ++r) {
    lower[r] = 0.0;
    upper[r] = rows_[r].sign == 0 ? 0.0 : kInfinity;
  }
}

void StickingConstraint::values(const ConstVectorRef& z, VectorRef g) const {
  for (int r = 0; r < rows(); ++r) {
    const double s = rows_[r].sign == 0 ? 1.0 : rows_[r].sign;
    g[r] = s * (z[rows_[r].to] - z[rows_[r].from]);
  }
}

void StickingConstraint::jacobian(const ConstVectorRef&, double* values) const {
  for (int r = 0; r < rows(); ++r) {
    const double s = rows_[r].sign == 0 ? 1.0 : rows_[r].sign;
    values[2 * r] = -s;
    values[2 * r + 1] = s;
  }
}

}  // namespace rbsf::trajopt
