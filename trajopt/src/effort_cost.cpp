#include "rbsf/trajopt/effort_cost.h"

namespace rbsf::trajopt {

VecU effortWeights(const RbsfModel& model) {
  const Cell& cell = model.cell();
  VecU w(model.controlDim());
  w[layout::kTauTheta] = 1.0 / (cell.base.torque_limit * cell.base.torque_limit);
  for (int i = 0; i < model.numFingers(); ++i)
    w[layout::fingerForce(i)] = 1.0 / (cell.fingers[i].force_limit * cell.fingers[i].force_limit);
  return w;
}

EffortCost::EffortCost(const RbsfModel& model, const DecisionLayout& layout,
                       const Schedule& schedule)
    : layout_(layout), schedule_(schedule), w_(effortWeights(model)) {}

double EffortCost::load(const ConstVectorRef& z, int k) const {
  const auto tau = z.segment(layout_.tau(k), w_.size());
  return tau.cwiseAbs2().dot(w_);
}

double EffortCost::value(const ConstVectorRef& z) const {
  double J = 0.0;
  for (int k = 0; k < layout_.intervals(); ++k) {
    const PhaseRun& run = schedule_.runOf(k);
    const double h = z[layout_.duration(schedule_.run_of_interval[k])] / run.intervals;
    J += 0.5 * h * (load(z, k) + load(z, k + 1));
  }
  return J;
}

void EffortCost::addGradient(const ConstVectorRef& z, VectorRef grad) const {
  const int nu = static_cast<int>(w_.size());
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    const int N = schedule_.runs[j].intervals;
    const double h = z[layout_.duration(j)] / N;
    for (int e = 0; e < 2; ++e)
      grad.segment(layout_.tau(k + e), nu) +=
          h * w_.cwiseProduct(z.segment(layout_.tau(k + e), nu));
    grad[layout_.duration(j)] += 0.5 / N * (load(z, k) + load(z, k + 1));
  }
}

// d^2/dtau_k^2 = h W from each adjacent interval; d^2/dtau_k dT_j = W tau_k / N_j.
void EffortCost::hessianStructure(HessianPattern& p) {
  const int nu = static_cast<int>(w_.size());
  hess_slots_.clear();
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int T = layout_.duration(schedule_.run_of_interval[k]);
    for (int e = 0; e < 2; ++e)
      for (int a = 0; a < nu; ++a) {
        const int c = layout_.tau(k + e) + a;
        hess_slots_.push_back(p.slot(c, c));
        hess_slots_.push_back(p.slot(T, c));
      }
  }
}

void EffortCost::addHessian(const ConstVectorRef& z, double sigma, double* values) const {
  const int nu = static_cast<int>(w_.size());
  const int* slot = hess_slots_.data();
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    const int N = schedule_.runs[j].intervals;
    const double h = z[layout_.duration(j)] / N;
    for (int e = 0; e < 2; ++e)
      for (int a = 0; a < nu; ++a) {
        values[*slot++] += sigma * h * w_[a];
        values[*slot++] += sigma * w_[a] * z[layout_.tau(k + e) + a] / N;
      }
  }
}

}  // namespace rbsf::trajopt
