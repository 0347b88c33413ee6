#pragma once
/// \file
/// \brief Conditions for turning the object (paper section 3, eqs. 25-28).

#include <Eigen/Core>

#include "rbsf/dynamics/core/model.h"

namespace rbsf {

/// \brief Contact point in its own contact frame (eq. 25), object frame:
///        c(xi_i) = -(alpha_n n(xi_i) + alpha_t t(xi_i)). alpha_t is the signed moment arm
///        of the normal line about the COM: I_o omega_o' = -sum(alpha_t,i f_n,i) (eq. 27).
struct ContactArms {
  double alpha_n = 0.0;  ///< [m]
  double alpha_t = 0.0;  ///< [m]
};

/// \brief alpha_n = -c.n, alpha_t = -c.t at contact i (call updateContacts first).
ContactArms contactArms(const ModelData& data, int i);

/// \brief The COM lies strictly inside the region bounded by the normals of contacts i
///        and j (paper Fig. 2): their normal lines pass on opposite sides of the COM
///        (alpha_t,i alpha_t,j < 0), so f_n >= 0 can turn the object either way.
bool comBetweenNormals(const ModelData& data, int i, int j);

/// \brief Range of the object's angular acceleration with every contact kept closed.
struct OmegaDotRange {
  bool feasible = false;    ///< some tau within limits keeps every contact closed
  double min = 0.0;         ///< smallest omega_o' [rad/s^2]
  double max = 0.0;         ///< largest omega_o' [rad/s^2]
  bool positive = false;    ///< omega_o' > 0 is achievable
  bool negative = false;    ///< omega_o' < 0 is achievable
  Eigen::VectorXd tau_max;  ///< a tau achieving max
  Eigen::VectorXd tau_min;  ///< a tau achieving min
};

/// \brief Exact range of omega_o' over every tau within the cell's limits such that all
///        contacts stay closed in phase U (delta_n = 0 with F_n >= 0, eqs. 21-22): two
///        linear programs in (tau, F_n),
///          min / max  (M^-1 (u - Q + G1 F_n))_phi
///          s.t.       A F_n + G1^T M^-1 B tau = -(h_n - G1^T M^-1 Q),  F_n >= 0,
///                     |tau_j| <= limit_j.
///        A sign counts as achievable when its extreme exceeds `tolerance` [rad/s^2].
/// \pre model.updateContacts(q, data) has been called for q.
OmegaDotRange omegaDotRange(const RbsfModel& model, const VecQ& q, const VecQ& v, ModelData& data,
                            double tolerance = 1e-9);

}  // namespace rbsf
