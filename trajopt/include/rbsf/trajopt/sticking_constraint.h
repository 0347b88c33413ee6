#pragma once
/// \file
/// \brief Sticking contacts keep their material point; sliding ones keep their direction.

#include "rbsf/trajopt/decision_layout.h"
#include "rbsf/trajopt/nlp_element.h"
#include "rbsf/trajopt/schedule.h"

namespace rbsf::trajopt {

/// \brief Linear rows on the foot-point parameters, per interval k (of run j, h = T_j / N_j)
///        and finger i:
///   xi_{k+1,i} - xi_{k,i} = 0            where contact i sticks on interval k (the contact
///                                        is fixed in the object frame, paper 2.2);
///   s (xi_{k+1,i} - xi_{k,i}) - w h >= 0 where it slides, when keep_slide_direction is set
///                                        and the plan's slide over the run had sign s != 0,
///                                        with w = min(min_slip_rate, half the plan's mean
///                                        |d xi/dt| over the run) [1/s]: the contact slides
///                                        one way (the replay does not stick where the plan
///                                        slides one way, nor slide back) and, with w > 0,
///                                        at a rate the replay cannot mistake for sticking.
class StickingConstraint final : public ConstraintSet {
 public:
  StickingConstraint(const DecisionLayout& layout, const Schedule& schedule,
                     bool keep_slide_direction, double min_slip_rate);

  std::string name() const override { return "sticking"; }
  int rows() const override { return static_cast<int>(rows_.size()); }
  void bounds(VectorRef lower, VectorRef upper) const override;
  void values(const ConstVectorRef& z, VectorRef g) const override;
  const std::vector<std::pair<int, int>>& structure() const override { return structure_; }
  void jacobian(const ConstVectorRef& z, double* values) const override;

 private:
  struct Row {
    int from, to;    ///< columns of xi_k,i and xi_{k+1},i
    int sign;        ///< 0: equality (stick); +-1: direction
    int duration;    ///< column of T_j
    double rate_dt;  ///< w / N_j: the row's coefficient of T_j (0: no such entry)
  };
  std::vector<Row> rows_;
  std::vector<std::pair<int, int>> structure_;
};

}  // namespace rbsf::trajopt
