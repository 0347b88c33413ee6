#pragma once
/// \file
/// \brief Penalty on the rate of change of tau (smooth torques for the cell).

#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/trajopt/decision_layout.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief J_smooth = w_s sum_k (tau_{k+1} - tau_k)^T W (tau_{k+1} - tau_k) / h_k: the exact
///        integral of tau_dot^T W tau_dot for tau linear on each interval, times the weight
///        w_s [s^2] (OptimizerSettings::smoothness_weight); W as effortWeights() [s].
class SmoothnessCost final : public CostTerm {
 public:
  SmoothnessCost(const RbsfModel& model, const DecisionLayout& layout, const Schedule& schedule,
                 double weight);
  std::string name() const override { return "smoothness"; }
  double value(const ConstVectorRef& z) const override;
  void addGradient(const ConstVectorRef& z, VectorRef grad) const override;
  void hessianStructure(HessianPattern& pattern) override;
  void addHessian(const ConstVectorRef& z, double sigma, double* values) const override;

 private:
  DecisionLayout layout_;
  const Schedule& schedule_;
  VecU w_;
  std::vector<int> hess_slots_;
  double weight_;
};

}  // namespace rbsf::trajopt
