#pragma once
/// \file
/// \brief What a support search reached (support_search.h), for a cell engineer when it
///        found no path: the part angles relative to the base and the world angles its
///        start tree reached, the reached pose closest to the goal, and the rules that refused
///        the moves that would have gone closer to the goal than any pose reached.
///
/// A refused move is counted against the first rule it breaks, checked in the order of
/// SupportRule: the base's angle limits, a finger's stroke limits, a finger whose line
/// misses the part's underside (or meets it too steeply), a retracted tip that would touch
/// the part, balance (the friction cones at the friction use and the normal-force floor),
/// a support the joints alone cannot fix, a run whose sliders cannot break loose from rest,
/// a step whose roles the contact-force law cannot keep (role_feasibility.h), and a stretch
/// blocked after its closed-loop run failed.

#include <array>
#include <string>

#include "rbsf/dynamics/core/placement.h"

namespace rbsf::planner {

/// \brief The rules a support move can break (file comment), in the order they are checked.
enum class SupportRule {
  kBaseLimit,
  kStroke,
  kReach,
  kClearance,
  kBalance,
  kUndetermined,
  kBreakaway,
  kLaw,
  kBlocked,
};
inline constexpr int kSupportRules = 9;

/// \brief A short name of `rule` for messages ("the base's angle limits", "balance ...").
const char* supportRuleText(SupportRule rule);

/// \brief The start tree's reach (file comment); angles in radians, poses in the world.
struct SupportReach {
  bool measured = false;          ///< false: no search ran
  double psi_min = 0.0;           ///< smallest part angle relative to the base reached [rad]
  double psi_max = 0.0;           ///< largest [rad]
  double phi_min = 0.0;           ///< smallest world part angle reached [rad]
  double phi_max = 0.0;           ///< largest [rad]
  Pose closest;                   ///< the reached world pose closest to the goal
  double closest_position = 0.0;  ///< its distance from the goal [m]
  double closest_angle = 0.0;     ///< its angle from the goal [rad] (signed, goal minus it)
  double closest_score = 0.0;     ///< the search's normalised distance (support_search.h)
  long poses = 0;                 ///< support states reached
  /// \brief Moves refused per rule (SupportRule order) that would have gone closer to the
  ///        goal than the closest pose reached so far.
  std::array<long, kSupportRules> refused{};

  /// \brief The rule that refused most such moves (kBalance when none was refused).
  SupportRule stoppedBy() const;
  /// \brief Combine the reach of another search of the same problem (ranges, closest pose,
  ///        counts).
  void merge(const SupportReach& other);
  /// \brief One line: "reached part angles -119..92 deg on the base (world -150..110 deg);
  ///        closest pose 0.21 m and 35 deg from the goal; moves beyond it refused by
  ///        breakaway (1200), balance (800), ...".
  std::string text() const;
};

}  // namespace rbsf::planner
