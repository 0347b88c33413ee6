#include "rbsf/trajopt/smoothness_cost.h"

#include "rbsf/trajopt/effort_cost.h"

namespace rbsf::trajopt {

SmoothnessCost::SmoothnessCost(const RbsfModel& model, const DecisionLayout& layout,
                               const Schedule& schedule, double weight)
    : layout_(layout), schedule_(schedule), w_(effortWeights(model)), weight_(weight) {}

double SmoothnessCost::value(const ConstVectorRef& z) const {
  const int nu = static_cast<int>(w_.size());
  double J = 0.0;
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    const double h = z[layout_.duration(j)] / schedule_.runs[j].intervals;
    const VecU d = z.segment(layout_.tau(k + 1), nu) - z.segment(layout_.tau(k), nu);
    J += weight_ * d.cwiseAbs2().dot(w_) / h;
  }
  return J;
}

void SmoothnessCost::addGradient(const ConstVectorRef& z, VectorRef grad) const {
  const int nu = static_cast<int>(w_.size());
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    const int N = schedule_.runs[j].intervals;
    const double h = z[layout_.duration(j)] / N;
    const VecU d = z.segment(layout_.tau(k + 1), nu) - z.segment(layout_.tau(k), nu);
    const VecU g = (2.0 * weight_ / h) * w_.cwiseProduct(d);
    grad.segment(layout_.tau(k + 1), nu) += g;
    grad.segment(layout_.tau(k), nu) -= g;
    grad[layout_.duration(j)] -= weight_ * d.cwiseAbs2().dot(w_) / (h * h * N);
  }
}

// With d = tau_{k+1} - tau_k: d^2/dd^2 = 2 w_s W / h (on tau_k, tau_k+1 with signs),
// d^2/dd dT = -2 w_s W d / (h^2 N), d^2/dT^2 = 2 w_s d^T W d / (h^3 N^2).
void SmoothnessCost::hessianStructure(HessianPattern& p) {
  const int nu = static_cast<int>(w_.size());
  hess_slots_.clear();
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int T = layout_.duration(schedule_.run_of_interval[k]);
    for (int a = 0; a < nu; ++a) {
      const int c0 = layout_.tau(k) + a, c1 = layout_.tau(k + 1) + a;
      hess_slots_.push_back(p.slot(c0, c0));
      hess_slots_.push_back(p.slot(c1, c1));
      hess_slots_.push_back(p.slot(c1, c0));
      hess_slots_.push_back(p.slot(T, c0));
      hess_slots_.push_back(p.slot(T, c1));
    }
    hess_slots_.push_back(p.slot(T, T));
  }
}

void SmoothnessCost::addHessian(const ConstVectorRef& z, double sigma, double* values) const {
  const int nu = static_cast<int>(w_.size());
  const int* slot = hess_slots_.data();
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    const int N = schedule_.runs[j].intervals;
    const double h = z[layout_.duration(j)] / N;
    double dWd = 0.0;
    for (int a = 0; a < nu; ++a) {
      const double d = z[layout_.tau(k + 1) + a] - z[layout_.tau(k) + a];
      const double s = sigma * 2.0 * weight_ * w_[a];
      values[*slot++] += s / h;
      values[*slot++] += s / h;
      values[*slot++] -= s / h;
      values[*slot++] += s * d / (h * h * N);
      values[*slot++] -= s * d / (h * h * N);
      dWd += w_[a] * d * d;
    }
    values[*slot++] += sigma * 2.0 * weight_ * dWd / (h * h * h * N * N);
  }
}

}  // namespace rbsf::trajopt
