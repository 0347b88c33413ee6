#pragma once
/// \file
/// \brief Static holding: can the mechanism keep the object at rest on the fingers?

#include <Eigen/Core>

#include "rbsf/dynamics/core/model.h"

namespace rbsf {

/// \brief Result of holdingTorques().
struct HoldingSolution {
  bool feasible = false;  ///< forces in the cones and tau within limits exist
  Eigen::VectorXd tau;    ///< the holding tau (order of layout), when feasible
  Eigen::VectorXd fn;     ///< normal forces per contact [N]
  Eigen::VectorXd ft;     ///< tangential forces per contact, along t_i [N]
};

/// \brief Hold the object at rest (v = 0, dv/dt = 0) on every finger: static balance
///        Q(q, 0) = u + G1 F_n + T F_t (eq. 18), i.e. the object rows G F = (0, m_o g0, 0)
///        with forces in the friction cones |f_t| <= mu_s f_n, and
///        tau = Q_R - [G1 T]_R [F_n; F_t] within the cell's limits. Among all such forces
///        the least-norm one is chosen (the same rule as phase C), so the returned tau
///        is the holding tau that loads the contacts least.
/// \pre model.updateContacts(q, data) has been called for q.
HoldingSolution holdingTorques(const RbsfModel& model, const VecQ& q, const ModelData& data);

}  // namespace rbsf
