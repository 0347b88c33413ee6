#include "rbsf/trajopt/effort_cost.h"

#include <algorithm>

namespace rbsf::trajopt {

VecU effortWeights(const RbsfModel& model) {
  const Cell& cell = model.cell();
  VecU w(model.controlDim());
  w[layout::kTauTheta] = 1.0 / (cell.base.torque_limit * cell.base.torque_limit);
  for (int i = 0; i < model.numFingers(); ++i)
    w[layout::fingerForce(i)] = 1.0 / (cell.fingers[i].force_limit * cell.fingers[i].force_limit);
  return w;
}

KnotQuadraticCost::KnotQuadraticCost(std::string name, const DecisionLayout& layout,
                                     const Schedule& schedule, int offset, Eigen::VectorXd weights)
    : name_(std::move(name)),
      layout_(layout),
      schedule_(schedule),
      offset_(offset),
      w_(std::move(weights)) {}

double KnotQuadraticCost::load(const ConstVectorRef& z, int k) const {
  return z.segment(column(k), w_.size()).cwiseAbs2().dot(w_);
}

double KnotQuadraticCost::value(const ConstVectorRef& z) const {
  double J = 0.0;
  for (int k = 0; k < layout_.intervals(); ++k) {
    const PhaseRun& run = schedule_.runOf(k);
    const double h = z[layout_.duration(schedule_.run_of_interval[k])] / run.intervals;
    J += 0.5 * h * (load(z, k) + load(z, k + 1));
  }
  return J;
}

void KnotQuadraticCost::addGradient(const ConstVectorRef& z, VectorRef grad) const {
  const int nw = static_cast<int>(w_.size());
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    const int N = schedule_.runs[j].intervals;
    const double h = z[layout_.duration(j)] / N;
    for (int e = 0; e < 2; ++e)
      grad.segment(column(k + e), nw) += h * w_.cwiseProduct(z.segment(column(k + e), nw));
    grad[layout_.duration(j)] += 0.5 * (load(z, k) + load(z, k + 1)) / N;
  }
}

// Per interval and end (share 1/2): d^2/dx^2 = h W; d^2/dx dT_j = W x / N_j.
void KnotQuadraticCost::hessianStructure(HessianPattern& p) {
  hess_slots_.clear();
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int T = layout_.duration(schedule_.run_of_interval[k]);
    for (int e = 0; e < 2; ++e)
      for (int a = 0; a < w_.size(); ++a) {
        const int c = column(k + e) + a;
        hess_slots_.push_back(p.slot(c, c));
        hess_slots_.push_back(p.slot(T, c));
      }
  }
}

void KnotQuadraticCost::addHessian(const ConstVectorRef& z, double sigma, double* values) const {
  const int* slot = hess_slots_.data();
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    const int N = schedule_.runs[j].intervals;
    const double h = z[layout_.duration(j)] / N;
    for (int e = 0; e < 2; ++e)
      for (int a = 0; a < w_.size(); ++a) {
        const double c = sigma * w_[a];
        values[*slot++] += c * h;
        values[*slot++] += c * z[column(k + e) + a] / N;
      }
  }
}

EffortCost::EffortCost(const RbsfModel& model, const DecisionLayout& layout,
                       const Schedule& schedule)
    : KnotQuadraticCost("effort", layout, schedule, layout.localTau(),
                        effortWeights(model).cast<double>()) {}

namespace {
Eigen::VectorXd forceWeights(const RbsfModel& model, double weight) {
  const double w_o = model.cell().object.mass * std::max(model.cell().gravity, 1.0);
  return Eigen::VectorXd::Constant(2 * model.numFingers(), weight / (w_o * w_o));
}
}  // namespace

ContactForceCost::ContactForceCost(const RbsfModel& model, const DecisionLayout& layout,
                                   const Schedule& schedule, double weight)
    : KnotQuadraticCost("contact_force", layout, schedule, layout.localFn(),
                        forceWeights(model, weight)) {}

}  // namespace rbsf::trajopt
