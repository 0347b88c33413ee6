#pragma once
// Shared by the controller tests: a certified support plan of the default cell in a file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "rbsf/controller/reorientation_controller.h"
#include "test_support.h"

namespace rbsf::controller {

inline const std::string kDefaultCell = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";

/// The -15 degree support plan of the default cell, planned by the CLI's pipeline through
/// the facade and written to a file, once per test binary.
inline const std::string& planFile() {
  static const std::string path = [] {
    ReorientationController c(kDefaultCell);
    ReorientationRequest r;
    r.problem.start = {0.1, 0.40, 0.0};
    r.problem.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
    r.method = planner::PipelineMethod::kAuto;
    // Budgets in work, not time: the same plan on a loaded machine (no clock).
    r.planner = rbsf::test::withoutClock(r.planner);
    r.planner.max_propagations = 200000;
    r.support.max_expansions = 100000;
    r.certificate.trials = 4;
    r.certificate.required_rate = 0.4;
    if (!c.plan(r)) throw std::runtime_error("plan() refused");
    c.wait();
    if (c.status() != ControllerStatus::kReady) throw std::runtime_error(c.result().message);
    const std::string file =
        ::testing::TempDir() + "support_plan_" + std::to_string(getpid()) + ".json";
    plan::writePlanJson(c.result().record, file);
    return file;
  }();
  return path;
}

}  // namespace rbsf::controller
