#pragma once
/// \file
/// \brief A cell: the RBSF mechanism, the object it carries and the friction between them
///        (docs/model.md "Files"). SI units; angles in radians.

#include <memory>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/faults.h"
#include "rbsf/dynamics/core/motion_limits.h"
#include "rbsf/dynamics/core/sensing.h"
#include "rbsf/dynamics/core/shape.h"

namespace rbsf {

/// \brief The rotational base.
struct BaseParams {
  double inertia = 0.0;       ///< I_b about the base axis [kg m^2]
  double theta_min = -M_PI;   ///< lower base angle limit [rad]
  double theta_max = M_PI;    ///< upper base angle limit [rad]
  double torque_limit = 0.0;  ///< |tau_theta| bound [N m]
};

/// \brief One single-jointed (prismatic) finger.
struct FingerParams {
  double r = 0.0;            ///< lateral offset along the base x axis [m]
  double stroke_min = 0.0;   ///< lower stroke limit of l_i [m]
  double stroke_max = 0.0;   ///< upper stroke limit of l_i [m]
  double mass = 0.0;         ///< carriage mass m_i [kg]
  double force_limit = 0.0;  ///< |tau_i| bound [N]
  double com_offset = 0.0;   ///< s_i: carriage COM at base point (r_i, l_i + s_i) [m]
  double inertia = 0.0;      ///< J_i: carriage inertia about its COM [kg m^2]
};

/// \brief The rigid workpart.
struct ObjectParams {
  std::shared_ptr<const Shape> shape;  ///< boundary in the object (COM) frame
  double mass = 0.0;                   ///< m_o [kg]
  double inertia = 0.0;                ///< I_o about the COM [kg m^2]
};

/// \brief Coulomb friction at the fingertips.
struct FrictionParams {
  double mu_static = 0.5;   ///< mu_s: bound of a sticking contact's force cone
  double mu_kinetic = 0.0;  ///< mu_k: sliding friction (the paper's 0 by default)
};

/// \brief Everything the model needs about one jig cell.
struct Cell {
  double gravity = 9.81;  ///< g0 [m/s^2]; gravity is (0, -g0) in the world frame
  BaseParams base;
  std::vector<FingerParams> fingers;
  ObjectParams object;
  FrictionParams friction;
  Sensing sensing;             ///< what the cell measures (sensing.h; defaults when absent)
  Uncertainty uncertainty;     ///< what a plan must tolerate (sensing.h; defaults when absent)
  MotionLimits motion_limits;  ///< how fast a plan may move the part (motion_limits.h)
  Faults faults;               ///< what trials draw beyond the uncertainty (faults.h; none)
  std::string name;            ///< file name or label, for messages

  /// \brief Number of fingers m.
  int numFingers() const { return static_cast<int>(fingers.size()); }

  /// \brief The bound on input j in tau order (state_layout.h): torque_limit [N m] for
  ///        tau_theta, finger j's force_limit [N] for tau_j, j >= 1.
  double inputLimit(int j) const;

  /// \brief Check every invariant the model relies on (positive masses and inertias,
  ///        ordered limits, 1 <= m <= kMaxFingers, a shape) and the ranges of the sensing
  ///        and uncertainty sections (non-negative noise, relative uncertainties in [0, 1)).
  /// \throws InputError naming the offending key.
  void validate() const;
};

}  // namespace rbsf
