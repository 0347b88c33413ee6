#include "rbsf/planner/kinodynamic/projection.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {

PhiThetaProjection::PhiThetaProjection(const ompl::base::StateSpace* space, double phi_cell,
                                       double theta_cell)
    : ompl::base::ProjectionEvaluator(space), phi_cell_(phi_cell), theta_cell_(theta_cell) {}

void PhiThetaProjection::defaultCellSizes() { cellSizes_ = {phi_cell_, theta_cell_}; }

void PhiThetaProjection::project(const ompl::base::State* state,
                                 Eigen::Ref<Eigen::VectorXd> projection) const {
  const double* x = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  projection[0] = x[layout::kPhi];
  projection[1] = x[layout::kTheta];
}

}  // namespace rbsf::planner
