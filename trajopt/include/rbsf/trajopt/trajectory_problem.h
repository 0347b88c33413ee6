#pragma once
/// \file
/// \brief The whole NLP, independent of the solver: variables, the stacked constraint sets
///        and the cost terms of one plan's refinement.
///
///   min  J_effort(z) + J_smooth(z)
///   s.t. collocation (dynamics), contact (foot points, contacts held / no penetration),
///        sticking (xi fixed while sticking, slide direction kept), friction cones,
///        variable bounds (limits, f_n >= 0, start, goal, at rest, durations).
/// Rows are stacked in that order; see each element's header for its maths.

#include <memory>
#include <string>
#include <vector>

#include "rbsf/trajopt/decision_variables.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/optimizer_settings.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief One refinement problem. Not copyable (the elements refer to its schedule).
class TrajectoryProblem {
 public:
  /// \brief Build the schedule and every element; ok() is false (why() says why) when the
  ///        plan cannot be scheduled.
  TrajectoryProblem(const RbsfModel& model, const plan::Plan& plan,
                    const OptimizerSettings& settings);
  TrajectoryProblem(const TrajectoryProblem&) = delete;
  TrajectoryProblem& operator=(const TrajectoryProblem&) = delete;

  bool ok() const { return ok_; }
  const std::string& why() const { return why_; }
  const Schedule& schedule() const { return schedule_; }
  const DecisionLayout& layout() const { return *layout_; }
  const DecisionVariables& variables() const { return *variables_; }
  const std::vector<std::unique_ptr<ConstraintSet>>& constraints() const { return sets_; }
  const std::vector<std::unique_ptr<CostTerm>>& costs() const { return costs_; }

  int size() const { return layout_->size(); }
  int rows() const { return rows_; }
  int nonZeros() const { return static_cast<int>(jac_rows_.size()); }
  /// \brief First row of constraint set s in the stacked g.
  int rowOffset(int s) const { return offsets_[s]; }

  void constraintBounds(Eigen::VectorXd& lower, Eigen::VectorXd& upper) const;
  double objective(const ConstVectorRef& z) const;
  void gradient(const ConstVectorRef& z, VectorRef grad) const;
  void constraintValues(const ConstVectorRef& z, VectorRef g) const;
  /// \brief Stacked Jacobian structure (row, column), in the order of jacobianValues().
  const std::vector<int>& jacobianRows() const { return jac_rows_; }
  const std::vector<int>& jacobianCols() const { return jac_cols_; }
  void jacobianValues(const ConstVectorRef& z, double* values) const;
  /// \brief Structure of the Hessian of the Lagrangian (lower triangle).
  const HessianPattern& hessianPattern() const { return hessian_; }
  /// \brief values = sigma d^2 J / dz^2 + sum_r lambda_r d^2 g_r / dz^2 (stacked lambda).
  void hessianValues(const ConstVectorRef& z, double sigma, const double* lambda,
                     double* values) const;

  /// \brief The effort integral of tau^T W tau alone (cost_after) [s].
  double effort(const ConstVectorRef& z) const;

  /// \brief The refined plan from a solution z (see PlanOptimizer::optimize).
  plan::Plan toPlan(const ConstVectorRef& z, const plan::Plan& input) const;

 private:
  const RbsfModel& model_;
  Schedule schedule_;
  bool ok_ = false;
  std::string why_;
  std::unique_ptr<DecisionLayout> layout_;
  std::unique_ptr<DecisionVariables> variables_;
  std::vector<std::unique_ptr<ConstraintSet>> sets_;
  std::vector<std::unique_ptr<CostTerm>> costs_;
  std::vector<int> offsets_;
  int rows_ = 0;
  std::vector<int> jac_rows_, jac_cols_;
  HessianPattern hessian_;
};

/// \brief The planner's effort: sum over segments of duration x tau^T W tau [s] (W as
///        effortWeights()); the integral for piecewise-constant tau.
double planEffort(const RbsfModel& model, const plan::Plan& plan);

}  // namespace rbsf::trajopt
