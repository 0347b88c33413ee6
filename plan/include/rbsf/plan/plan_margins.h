#pragma once
/// \file
/// \brief What the planner held a plan to: the margins its refinement keeps. The support
///        planner states them (planner/support_planner.h); the optimiser refines a support
///        plan within them (trajopt/plan_refinement.h).

namespace rbsf::plan {

/// \brief What the planner held a plan to, which its refinement keeps.
struct PlanMargins {
  /// \brief A support plan (planner/support_planner.h): quasi-static, its contacts' roles
  ///        stated; refined on those roles within the margins below and near its path
  ///        (trajopt::supportOptimizerSettings). false: a kinodynamic plan.
  bool support = false;
  double friction_use = 1.0;   ///< sticking |f_t| <= friction_use x mu_s f_n [-]
  double normal_margin = 0.0;  ///< every relied-on contact's f_n >= normal_margin x m_o g0 [-]
};

}  // namespace rbsf::plan
