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

/// \brief A refinement of an exact plan: returns the plan to keep with its certificate made
///        with the given settings, sets `refined` when that is the refined one and `note` to
///        why not.
using RefineStep = std::function<Plan(const Plan& plan, const CertificateSettings& certificate,
                                      bool& refined, std::string& note)>;

}  // namespace rbsf::plan
