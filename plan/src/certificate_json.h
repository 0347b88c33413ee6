#pragma once
// The certificate's JSON object (certificate_report.h), shared by plan files (plan.cpp) and
// rbsf-replay's report (certificateJsonText).

#include <nlohmann/json.hpp>
#include <string>

#include "rbsf/plan/certificate_report.h"

namespace rbsf::plan {

/// \brief The certificate as a JSON object (keys in plan.h's table).
nlohmann::json certificateJson(const Certificate& certificate);

/// \brief Read it back. \throws InputError naming `where` and the key when malformed.
Certificate readCertificateJson(const nlohmann::json& j, const std::string& where);

}  // namespace rbsf::plan
