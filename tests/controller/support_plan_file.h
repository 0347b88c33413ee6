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

/// A support turn of the default cell from (0.1, 0.40, 0) by `degrees`, planned by the
/// CLI's pipeline through the facade (refined where at least as good when `optimize`),
/// certified by `trials` trials at `required_rate`, written to a file named after `name`.
inline std::string plannedFile(double degrees, bool optimize, int trials, double required_rate,
                               const std::string& name) {
  ReorientationController c(kDefaultCell);
  ReorientationRequest r;
  r.problem.start = {0.1, 0.40, 0.0};
  r.problem.goal = {0.1, 0.40, degrees * M_PI / 180.0};
  r.method = planner::PipelineMethod::kAuto;
  r.optimize = optimize;
  // Budgets in work, not time: the same plan on a loaded machine (no clock).
  r.planner = rbsf::test::withoutClock(r.planner);
  r.planner.max_propagations = 200000;
  r.support.max_expansions = 100000;
  r.certificate.trials = trials;
  r.certificate.required_rate = required_rate;
  if (!c.plan(r)) throw std::runtime_error("plan() refused");
  c.wait();
  if (c.status() != ControllerStatus::kReady) throw std::runtime_error(c.result().message);
  const std::string file = ::testing::TempDir() + name + "_" + std::to_string(getpid()) + ".json";
  plan::writePlanJson(c.result().record, file);
  return file;
}

/// The -15 degree support plan (the planner's), once per test binary.
inline const std::string& planFile() {
  static const std::string path = plannedFile(-15.0, false, 4, 0.4, "support_plan");
  return path;
}

}  // namespace rbsf::controller
