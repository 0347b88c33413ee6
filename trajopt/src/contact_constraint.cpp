#include "rbsf/trajopt/contact_constraint.h"

namespace rbsf::trajopt {

namespace {
constexpr int kLocal = 6;  // x, y, phi, theta, l_i, xi_i
}

ContactConstraint::ContactConstraint(const RbsfModel& model, const DecisionLayout& layout,
                                     const Schedule& schedule)
    : model_(model), layout_(layout), schedule_(schedule), m_(model.numFingers()) {
  int cols[kLocal];
  for (int k = 0; k < layout_.knots(); ++k)
    for (int i = 0; i < m_; ++i) {
      columns(k, i, cols);
      for (int r = 0; r < rowsAt(k); ++r)
        for (int c = 0; c < kLocal; ++c) structure_.emplace_back(row(k, i) + r, cols[c]);
    }
}

void ContactConstraint::columns(int k, int i, int* cols) const {
  cols[0] = layout_.q(k) + layout::kX;
  cols[1] = layout_.q(k) + layout::kY;
  cols[2] = layout_.q(k) + layout::kPhi;
  cols[3] = layout_.q(k) + layout::kTheta;
  cols[4] = layout_.q(k) + layout::stroke(i);
  cols[5] = layout_.xi(k) + i;
}

void ContactConstraint::bounds(VectorRef lower, VectorRef upper) const {
  for (int k = 0; k < layout_.knots(); ++k)
    for (int i = 0; i < m_; ++i) {
      const int r = row(k, i);
      lower[r] = upper[r] = 0.0;
      if (k == 0) continue;
      const bool on = schedule_.knotRole(k, i) != ContactRole::kOff;
      lower[r + 1] = on ? 0.0 : -kInfinity;
      upper[r + 1] = 0.0;
    }
}

void ContactConstraint::values(const ConstVectorRef& z, VectorRef g) const {
  int cols[kLocal];
  double local[kLocal];
  for (int k = 0; k < layout_.knots(); ++k)
    for (int i = 0; i < m_; ++i) {
      columns(k, i, cols);
      for (int c = 0; c < kLocal; ++c) local[c] = z[cols[c]];
      double te, ne;
      residual<double>(i, local, te, ne);
      g[row(k, i)] = te;
      if (k > 0) g[row(k, i) + 1] = ne;
    }
}

void ContactConstraint::jacobian(const ConstVectorRef& z, double* values) const {
  using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, kLocal, 1>>;
  int cols[kLocal];
  AD local[kLocal];
  std::size_t e = 0;
  for (int k = 0; k < layout_.knots(); ++k)
    for (int i = 0; i < m_; ++i) {
      columns(k, i, cols);
      for (int c = 0; c < kLocal; ++c) local[c] = AD(z[cols[c]], kLocal, c);
      AD te, ne;
      residual<AD>(i, local, te, ne);
      for (int c = 0; c < kLocal; ++c) values[e++] = te.derivatives()[c];
      if (k > 0)
        for (int c = 0; c < kLocal; ++c) values[e++] = ne.derivatives()[c];
    }
}

void ContactConstraint::hessianStructure(HessianPattern& pattern) {
  int cols[kLocal];
  hess_slots_.clear();
  for (int k = 0; k < layout_.knots(); ++k)
    for (int i = 0; i < m_; ++i) {
      columns(k, i, cols);
      for (int a = 0; a < kLocal; ++a)
        for (int b = 0; b <= a; ++b) hess_slots_.push_back(pattern.slot(cols[a], cols[b]));
    }
}

void ContactConstraint::addHessian(const ConstVectorRef& z, const double* lambda,
                                   double* values) const {
  int cols[kLocal];
  double x[kLocal];
  AD6x2 local[kLocal];
  const int* slot = hess_slots_.data();
  for (int k = 0; k < layout_.knots(); ++k)
    for (int i = 0; i < m_; ++i) {
      columns(k, i, cols);
      for (int c = 0; c < kLocal; ++c) x[c] = z[cols[c]];
      seedSecondOrder(x, local);
      AD6x2 te, ne;
      residual<AD6x2>(i, local, te, ne);
      const int r = row(k, i);
      const double ln = k == 0 ? 0.0 : lambda[r + 1];
      const AD6x2 phi = lambda[r] * te + ln * ne;
      for (int a = 0; a < kLocal; ++a)
        for (int b = 0; b <= a; ++b) values[*slot++] += phi.derivatives()[a].derivatives()[b];
    }
}

}  // namespace rbsf::trajopt
