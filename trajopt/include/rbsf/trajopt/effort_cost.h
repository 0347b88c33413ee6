#pragma once
/// \file
/// \brief The effort integral of tau^T W tau (issue 5's measure of a plan's cost).

#include <vector>

#include "rbsf/dynamics/model.h"
#include "rbsf/trajopt/decision_layout.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief W = diag(1 / tau_limit_j^2) (base torque limit, finger force limits): tau^T W tau
///        is dimensionless, so the integral is in seconds at full load.
VecU effortWeights(const RbsfModel& model);

/// \brief J_effort = sum_k h_k / 2 (tau_k^T W tau_k + tau_{k+1}^T W tau_{k+1}), h_k = T_j / N_j
///        (trapezoidal integral of tau^T W tau over the plan) [s].
class EffortCost final : public CostTerm {
 public:
  EffortCost(const RbsfModel& model, const DecisionLayout& layout, const Schedule& schedule);
  std::string name() const override { return "effort"; }
  double value(const ConstVectorRef& z) const override;
  void addGradient(const ConstVectorRef& z, VectorRef grad) const override;
  void hessianStructure(HessianPattern& pattern) override;
  void addHessian(const ConstVectorRef& z, double sigma, double* values) const override;

 private:
  double load(const ConstVectorRef& z, int k) const;  ///< tau_k^T W tau_k

  DecisionLayout layout_;
  const Schedule& schedule_;
  VecU w_;
  std::vector<int> hess_slots_;
};

}  // namespace rbsf::trajopt
