#pragma once
/// \file
/// \brief Trapezoidal integrals of quadratic forms of knot variables: the effort integral
///        of tau^T W tau (the measure of a plan's cost the optimiser reports) and a small
///        contact-force regularisation.

#include <string>
#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/trajopt/decision_layout.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief W = diag(1 / tau_limit_j^2) (base torque limit, finger force limits): tau^T W tau
///        is dimensionless, so the integral is in seconds at full load.
VecU effortWeights(const RbsfModel& model);

/// \brief J = sum_k h_k / 2 (x_k^T W x_k + x_{k+1}^T W x_{k+1}) (trapezoidal),
///        h_k = T_j / N_j, for the block x_k of knot k that starts at local offset `offset`
///        with diagonal weights W.
class KnotQuadraticCost : public CostTerm {
 public:
  KnotQuadraticCost(std::string name, const DecisionLayout& layout, const Schedule& schedule,
                    int offset, Eigen::VectorXd weights);
  std::string name() const override { return name_; }
  double value(const ConstVectorRef& z) const override;
  void addGradient(const ConstVectorRef& z, VectorRef grad) const override;
  void hessianStructure(HessianPattern& pattern) override;
  void addHessian(const ConstVectorRef& z, double sigma, double* values) const override;

 private:
  double load(const ConstVectorRef& z, int k) const;  ///< x_k^T W x_k
  int column(int k) const { return layout_.knot(k) + offset_; }

  std::string name_;
  DecisionLayout layout_;
  const Schedule& schedule_;
  int offset_;
  Eigen::VectorXd w_;
  std::vector<int> hess_slots_;
};

/// \brief The effort: x = tau, W = effortWeights() [s].
class EffortCost final : public KnotQuadraticCost {
 public:
  EffortCost(const RbsfModel& model, const DecisionLayout& layout, const Schedule& schedule);
};

/// \brief weight x the integral of sum_i (f_n,i^2 + f_t,i^2) / W_o^2 (forces per knot,
///        decision_layout.h), W_o = m_o max(g0, 1)
///        the object's weight [s]. Contact forces of several sticking contacts are
///        statically indeterminate (docs/model.md, phase C); this picks the least-norm ones and
///        keeps the NLP's Hessian regular in those directions. Small (default 1e-3), so the
///        effort dominates.
class ContactForceCost final : public KnotQuadraticCost {
 public:
  ContactForceCost(const RbsfModel& model, const DecisionLayout& layout, const Schedule& schedule,
                   double weight);
};

}  // namespace rbsf::trajopt
