#include "rbsf/planner/support/support_reach.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

namespace rbsf::planner {

const char* supportRuleText(SupportRule rule) {
  switch (rule) {
    case SupportRule::kBaseLimit:
      return "the base's angle limits";
    case SupportRule::kStroke:
      return "a finger's stroke limits";
    case SupportRule::kReach:
      return "a finger's line missing the part's underside";
    case SupportRule::kClearance:
      return "a retracted tip touching the part";
    case SupportRule::kBalance:
      return "balance (friction cones, normal-force floor)";
    case SupportRule::kUndetermined:
      return "a support the joints cannot fix";
    case SupportRule::kBreakaway:
      return "breakaway (sliders that cannot break loose from rest)";
    case SupportRule::kLaw:
      return "the law's forces (no input keeps the contacts' roles)";
    case SupportRule::kBlocked:
      return "a stretch whose closed-loop run failed";
  }
  return "";
}

SupportRule SupportReach::stoppedBy() const {
  const auto most = std::max_element(refused.begin(), refused.end());
  if (*most == 0) return SupportRule::kBalance;
  return static_cast<SupportRule>(most - refused.begin());
}

void SupportReach::merge(const SupportReach& other) {
  if (!other.measured) return;
  if (!measured) {
    *this = other;
    return;
  }
  psi_min = std::min(psi_min, other.psi_min);
  psi_max = std::max(psi_max, other.psi_max);
  phi_min = std::min(phi_min, other.phi_min);
  phi_max = std::max(phi_max, other.phi_max);
  if (other.closest_score < closest_score) {
    closest = other.closest;
    closest_position = other.closest_position;
    closest_angle = other.closest_angle;
    closest_score = other.closest_score;
  }
  poses += other.poses;
  for (int r = 0; r < kSupportRules; ++r) refused[r] += other.refused[r];
}

std::string SupportReach::text() const {
  if (!measured) return "no search ran";
  const double deg = 180.0 / M_PI;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "reached part angles %.0f..%.0f deg on the base (world %.0f..%.0f deg) in %ld "
                "supports; closest pose (%.3f m, %.3f m, %.1f deg), %.3f m and %.1f deg from the "
                "goal",
                psi_min * deg, psi_max * deg, phi_min * deg, phi_max * deg, poses, closest.x,
                closest.y, closest.phi * deg, closest_position, std::abs(closest_angle) * deg);
  std::string s = buf;
  std::vector<int> order(kSupportRules);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return refused[a] > refused[b]; });
  std::string rules;
  for (int r : order) {
    if (refused[r] == 0) break;
    rules += (rules.empty() ? "" : ", ") +
             std::string(supportRuleText(static_cast<SupportRule>(r))) + " " +
             std::to_string(refused[r]);
  }
  s += rules.empty() ? "; no move beyond it was tried" : "; moves beyond it refused by " + rules;
  return s;
}

}  // namespace rbsf::planner
