#pragma once
/// \file
/// \brief Coulomb cones of the sticking contacts (docs/model.md "Phases", paper eq. 7).

#include "rbsf/trajopt/decision_layout.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief For every knot k whose forces have contact i sticking (Schedule::forceRole; its
///        f_t is free), the linearised cone |f_t| <= margin mu_s f_n as two rows <= 0 [N]:
///   f_t,k,i - margin mu_s f_n,k,i <= 0,    -f_t,k,i - margin mu_s f_n,k,i <= 0.
/// With f_n >= 0 (variable bounds) this is the planar cone exactly; margin < 1 keeps the
/// forces off its edges so the replay does not start to slip. A free touch (stated F) keeps
/// the margin too: with the whole cone the 45 degree support plan's refinement put its two
/// free tips on the cone's edge, they slid in the replay and the joints no longer held the
/// part for 0.67 s.
class FrictionConeConstraint final : public ConstraintSet {
 public:
  FrictionConeConstraint(const DecisionLayout& layout, const Schedule& schedule, double mu_s,
                         double margin);

  std::string name() const override { return "friction_cone"; }
  int rows() const override { return 2 * static_cast<int>(knots_.size()); }
  void bounds(VectorRef lower, VectorRef upper) const override;
  void values(const ConstVectorRef& z, VectorRef g) const override;
  const std::vector<std::pair<int, int>>& structure() const override { return structure_; }
  void jacobian(const ConstVectorRef& z, double* values) const override;

 private:
  std::vector<std::pair<int, int>> knots_;  ///< (column of f_n, column of f_t)
  double mu_;                               ///< margin * mu_s
  std::vector<std::pair<int, int>> structure_;
};

}  // namespace rbsf::trajopt
