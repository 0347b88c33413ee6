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
/// forces off its edges so the replay does not start to slip. A contact its run does not
/// rely on (PhaseRun::relied false: a free touch) keeps the whole cone, margin 1.
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
  struct Knot {
    int fn, ft;  ///< columns of f_n and f_t
    double mu;   ///< margin x mu_s, or mu_s for a contact not relied on
  };
  std::vector<Knot> knots_;
  std::vector<std::pair<int, int>> structure_;
};

}  // namespace rbsf::trajopt
