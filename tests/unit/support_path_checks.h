#pragma once
// Checks of support paths shared by the support search's and the simple turns' tests.
#include <cmath>
#include <cstddef>
#include <vector>

#include "rbsf/planner/support/support_search.h"

namespace rbsf::planner {

/// Whether some sliding contact of `set` slips more than 0.1 mm in `slip`. Written here
/// again on purpose (planner::slidersSlip is what these checks test, not their oracle).
inline bool anySliderSlips(const ContactSet& set, const VecC& slip) {
  for (int i = 0; i < slip.size(); ++i)
    if (set.touches(i) && !set.sticks(i) && std::abs(slip[i]) > 1e-4) return true;
  return false;
}

/// The steps where the runs of `path` start sliding (a run's first move that slips a slider;
/// the moves before it leave the part at rest) and do not break away there, with that move's
/// slip (SupportGeometry::breaksAway).
inline std::vector<SupportStep> runStartsThatStayStuck(SupportGeometry& geometry,
                                                       const SupportPath& path) {
  std::vector<SupportStep> out;
  bool resting = true;
  for (std::size_t i = 0; i + 1 < path.steps.size(); ++i) {
    const SupportStep& a = path.steps[i];
    const SupportStep& b = path.steps[i + 1];
    if (i > 0 && path.steps[i - 1].set != a.set) resting = true;
    if (a.set != b.set) continue;
    const VecC slip = geometry.slipDirections(a.q, b.q);
    if (!resting || !anySliderSlips(a.set, slip)) continue;
    resting = false;
    if (!geometry.breaksAway(a.q, a.set, slip)) out.push_back(a);
  }
  return out;
}

}  // namespace rbsf::planner
