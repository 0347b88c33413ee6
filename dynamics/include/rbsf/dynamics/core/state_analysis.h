#pragma once
/// \file
/// \brief Everything the model says about one state (q, v, tau), gathered for reports
///        (rbsf-analyze) and for callers that want the whole picture at once.

#include <Eigen/Core>
#include <vector>

#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/phase.h"
#include "rbsf/dynamics/core/rotation_analysis.h"

namespace rbsf {

/// \brief Per-contact part of StateAnalysis (world frame, SI units).
struct ContactReport {
  double xi = 0.0;       ///< boundary parameter of the contact
  double gap = 0.0;      ///< tip-to-boundary signed distance [m]
  Vec2 normal;           ///< inward normal n_i
  double f_n = 0.0;      ///< phase-U normal force (eqs. 21-24) [N]
  double delta_n = 0.0;  ///< phase-U normal relative acceleration [m/s^2]
  ContactArms arms;      ///< alpha_n, alpha_t (eq. 25) [m]
};

/// \brief The analysis of one state.
struct StateAnalysis {
  std::vector<ContactReport> contacts;
  Eigen::VectorXd accel;          ///< phase-U accelerations (eq. 20), order of q
  double sigma_min = 0.0;         ///< smallest singular value of G1
  bool determinate = false;       ///< sigma_min > kDeterminacyThreshold
  PhaseClassification phase;      ///< C, P or U with that phase's forces/accelerations
  bool phase_c_feasible = false;  ///< sticking at every contact fits the cones at this tau
  OmegaDotRange omega_dot;        ///< achievable omega_o' with contacts closed (paper 3)
  std::vector<std::pair<int, int>> com_regions;  ///< contact pairs whose normals enclose the COM
  bool com_in_end_region = false;                ///< the pair of outermost fingers encloses the COM
  HoldingSolution holding;                       ///< static holding at rest (v = 0)
};

/// \brief G1's smallest singular value below which the model is called indeterminate.
inline constexpr double kDeterminacyThreshold = 1e-8;

/// \brief Largest |gap| [m] at which a fingertip counts as on the boundary.
inline constexpr double kContactGapTolerance = 1e-6;

/// \brief Analyse (q, v, tau) with every finger touching.
/// \throws InputError naming the first finger whose |gap| exceeds kContactGapTolerance.
StateAnalysis analyzeState(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau);

}  // namespace rbsf
