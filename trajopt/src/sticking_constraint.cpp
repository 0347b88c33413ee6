#include "rbsf/trajopt/sticking_constraint.h"

#include <algorithm>

namespace rbsf::trajopt {

StickingConstraint::StickingConstraint(const DecisionLayout& layout, const Schedule& schedule,
                                       bool keep_slide_direction, double min_slip_rate) {
  for (int k = 0; k < layout.intervals(); ++k)
    for (int i = 0; i < layout.fingers(); ++i) {
      const ContactRole role = schedule.role(k, i);
      const PhaseRun& run = schedule.runOf(k);
      const int dir = run.slide_direction[i];
      const int T = layout.duration(schedule.run_of_interval[k]);
      if (role == ContactRole::kStick) {
        rows_.push_back({layout.xi(k) + i, layout.xi(k + 1) + i, 0, T, 0.0});
      } else if (role == ContactRole::kSlide && keep_slide_direction && dir != 0) {
        const double w = std::min(min_slip_rate, 0.5 * run.slide_rate[i]);
        rows_.push_back({layout.xi(k) + i, layout.xi(k + 1) + i, dir, T, w / run.intervals});
      }
    }
  for (int r = 0; r < rows(); ++r) {
    structure_.emplace_back(r, rows_[r].from);
    structure_.emplace_back(r, rows_[r].to);
    if (rows_[r].rate_dt > 0.0) structure_.emplace_back(r, rows_[r].duration);
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
    const Row& row = rows_[r];
    g[r] = row.sign == 0 ? z[row.to] - z[row.from]
                         : row.sign * (z[row.to] - z[row.from]) - row.rate_dt * z[row.duration];
  }
}

void StickingConstraint::jacobian(const ConstVectorRef&, double* values) const {
  for (const Row& row : rows_) {
    const double s = row.sign == 0 ? 1.0 : row.sign;
    *values++ = -s;
    *values++ = s;
    if (row.rate_dt > 0.0) *values++ = -row.rate_dt;
  }
}

}  // namespace rbsf::trajopt
