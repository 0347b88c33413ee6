#include "rbsf/trajopt/internal_force_constraint.h"

#include <algorithm>
#include <cmath>

namespace rbsf::trajopt {

namespace {
constexpr int kN = InternalForceConstraint::kLocal;
using AD14 = ADN<kN>;
using AD14x2 = ADNx2<kN>;
}  // namespace

InternalForceConstraint::InternalForceConstraint(const RbsfModel& model,
                                                 const DecisionLayout& layout,
                                                 const Schedule& schedule)
    : model_(model) {
  const int m = layout.fingers();
  for (int k = 0; k < layout.knots(); ++k) {
    std::vector<int> sticking;
    for (int i = 0; i < m; ++i)
      if (schedule.forceRole(k, i) == ContactRole::kStick) sticking.push_back(i);
    for (std::size_t a = 0; a + 2 < sticking.size(); ++a) {
      std::array<int, kLocal> cols{};
      cols[0] = layout.q(k) + layout::kPhi;
      cols[1] = layout.q(k) + layout::kTheta;
      for (int p = 0; p < 3; ++p) {
        const int i = sticking[a + p];
        cols[2 + p] = layout.q(k) + layout::stroke(i);
        cols[5 + p] = layout.fn(k) + i;
        cols[8 + p] = layout.ft(k) + i;
        cols[11 + p] = layout.xi(k) + i;
      }
      rows_.push_back(cols);
    }
  }
  for (int r = 0; r < rows(); ++r)
    for (int c = 0; c < kLocal; ++c) structure_.emplace_back(r, rows_[r][c]);
}

void InternalForceConstraint::bounds(VectorRef lower, VectorRef upper) const {
  lower.setZero();
  upper.setZero();
}

void InternalForceConstraint::values(const ConstVectorRef& z, VectorRef g) const {
  double local[kN];
  for (int r = 0; r < rows(); ++r) {
    for (int c = 0; c < kN; ++c) local[c] = z[rows_[r][c]];
    g[r] = internalForceResidual<double>(model_, local);
  }
}

void InternalForceConstraint::jacobian(const ConstVectorRef& z, double* values) const {
  AD14 local[kN];
  for (const auto& cols : rows_) {
    for (int c = 0; c < kN; ++c) local[c] = AD14(z[cols[c]], kN, c);
    const AD14 g = internalForceResidual<AD14>(model_, local);
    for (int c = 0; c < kN; ++c) *values++ = g.derivatives()[c];
  }
}

void InternalForceConstraint::hessianStructure(HessianPattern& pattern) {
  hess_slots_.clear();
  for (const auto& cols : rows_)
    for (int a = 0; a < kN; ++a)
      for (int b = 0; b <= a; ++b) hess_slots_.push_back(pattern.slot(cols[a], cols[b]));
}

void InternalForceConstraint::addHessian(const ConstVectorRef& z, const double* lambda,
                                         double* values) const {
  double x[kN];
  AD14x2 local[kN];
  const int* slot = hess_slots_.data();
  for (int r = 0; r < rows(); ++r) {
    for (int c = 0; c < kN; ++c) x[c] = z[rows_[r][c]];
    seedSecondOrder<kN>(x, local);
    const AD14x2 g = internalForceResidual<AD14x2>(model_, local);
    for (int a = 0; a < kN; ++a)
      for (int b = 0; b <= a; ++b)
        values[*slot++] += lambda[r] * g.derivatives()[a].derivatives()[b];
  }
}

}  // namespace rbsf::trajopt
