#include "rbsf/planner/planner_settings.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::planner {

const std::array<KinodynamicPlanner, 5>& kinodynamicPlanners() {
  static const std::array<KinodynamicPlanner, 5> all = {
      KinodynamicPlanner::kKPIECE1, KinodynamicPlanner::kRRT, KinodynamicPlanner::kSST,
      KinodynamicPlanner::kEST, KinodynamicPlanner::kPDST};
  return all;
}

const char* toString(KinodynamicPlanner planner) {
  switch (planner) {
    case KinodynamicPlanner::kKPIECE1:
      return "KPIECE1";
    case KinodynamicPlanner::kRRT:
      return "RRT";
    case KinodynamicPlanner::kSST:
      return "SST";
    case KinodynamicPlanner::kEST:
      return "EST";
    case KinodynamicPlanner::kPDST:
      return "PDST";
  }
  return "?";
}

std::optional<KinodynamicPlanner> parsePlanner(std::string_view name) {
  for (KinodynamicPlanner p : kinodynamicPlanners())
    if (name == toString(p)) return p;
  return std::nullopt;
}

void checkSettings(const DecisiveModes& rule) {
  if (rule.settle_steps < 0)
    throw InputError("decisive modes: settle_steps must be >= 0 (got " +
                     std::to_string(rule.settle_steps) + ")");
  if (!(rule.cone_margin > 0.0 && rule.cone_margin <= 1.0))
    throw InputError("decisive modes: cone_margin must be in (0, 1] (got " +
                     std::to_string(rule.cone_margin) + ")");
}

void checkSettings(const PlannerSettings& s) {
  const auto& all = kinodynamicPlanners();
  if (std::find(all.begin(), all.end(), s.planner) == all.end())
    throw InputError("unknown planner " + std::to_string(static_cast<int>(s.planner)) +
                     " (choose KPIECE1, RRT, SST, EST or PDST)");
  if (!(s.time_limit > 0.0))
    throw InputError("time limit: must be positive (infinity: no clock, the budgets alone)");
  if (s.steps_per_control < 1 || s.min_control_steps < 1 ||
      s.max_control_steps < s.min_control_steps || s.sample_steps < 1)
    throw InputError("control steps must be positive and ordered");
  checkSettings(s.decisive_modes);
}

void checkTolerance(const GoalTolerance& t) {
  if (!(t.position > 0.0) || !(t.angle > 0.0) || !std::isfinite(t.position) ||
      !std::isfinite(t.angle))
    throw InputError("goal tolerances must be positive and finite");
}

}  // namespace rbsf::planner
