#pragma once
/// \file
/// \brief The refinement hook of the pipeline (planner/reorientation_pipeline.h), declared
///        here so that the optimiser (trajopt::refinementStep) provides it without
///        depending on the planner: planner and trajopt are siblings on top of this module.

#include <functional>
#include <string>

#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan.h"

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

/// \brief A refinement of an exact plan: returns the plan to keep with its certificate made
///        with the given settings, sets `refined` when that is the refined one and `note` to
///        why not.
using RefineStep =
    std::function<Plan(const Plan& plan, const PlanMargins& margins,
                       const CertificateSettings& certificate, bool& refined, std::string& note)>;

}  // namespace rbsf::plan
