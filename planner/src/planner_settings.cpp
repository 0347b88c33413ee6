#include "rbsf/planner/planner_settings.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::planner {

void checkSettings(const DecisiveModes& rule) {
  if (rule.settle_steps < 0)
    throw InputError("decisive modes: settle_steps must be >= 0 (got " +
                     std::to_string(rule.settle_steps) + ")");
  if (!(rule.cone_margin > 0.0 && rule.cone_margin <= 1.0))
    throw InputError("decisive modes: cone_margin must be in (0, 1] (got " +
                     std::to_string(rule.cone_margin) + ")");
}

void checkSettings(const PlannerSettings& s) {
  const auto& names = plannerNames();
  if (std::find(names.begin(), names.end(), s.planner) == names.end())
    throw InputError("unknown planner '" + s.planner + "' (choose KPIECE1, RRT, SST, EST or PDST)");
  if (!(s.time_limit > 0.0) || !std::isfinite(s.time_limit))
    throw InputError("time limit: must be positive and finite");
  if (s.steps_per_control < 1 || s.min_control_steps < 1 ||
      s.max_control_steps < s.min_control_steps || s.sample_steps < 1)
    throw InputError("control steps must be positive and ordered");
  if (!(s.position_tolerance > 0.0) || !(s.angle_tolerance > 0.0))
    throw InputError("goal tolerances must be positive");
  checkSettings(s.decisive_modes);
}

}  // namespace rbsf::planner
