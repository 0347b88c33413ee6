#pragma once
/// \file
/// \brief KPIECE/EST/PDST projection: (object angle phi, base angle theta), the two
///        coordinates a reorientation has to explore. Cell sizes set by hand (default 0.1
///        rad each).

#include <ompl/base/ProjectionEvaluator.h>

namespace rbsf::planner {

/// \brief Projects a SimStateSpace state to (phi, theta).
class PhiThetaProjection : public ompl::base::ProjectionEvaluator {
 public:
  PhiThetaProjection(const ompl::base::StateSpace* space, double phi_cell, double theta_cell);

  unsigned int getDimension() const override { return 2; }
  void defaultCellSizes() override;
  void project(const ompl::base::State* state,
               Eigen::Ref<Eigen::VectorXd> projection) const override;

 private:
  double phi_cell_, theta_cell_;
};

}  // namespace rbsf::planner
