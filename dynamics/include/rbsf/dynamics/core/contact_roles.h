#pragma once
/// \file
/// \brief What a plan asks of each contact over a stretch of time: stick, slide one way or
///        the other, or let go. The control law keeps each contact in its role
///        (contact_force_qp.h); plan files carry the roles per segment (plan.h `contacts`).
///
/// Text form, one letter per finger in finger order: `S` stick (the tip keeps its point of
/// the part), `+` slide with slip T_i^T v > 0, `-` slide with slip T_i^T v < 0 (T_i the
/// tangential column of docs/model.md, so the slip is the part's boundary point moving
/// past the tip along t_i), `L` lifted (the finger does not touch; its stroke is
/// position-controlled), `F` free (the plan neither relies on the contact nor lifts it: a
/// tip that touches lightly, within its cone, with no margin asked). Example: "LS+" for finger 1
/// lifted, finger 2 sticking, finger 3 sliding in +t.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief The role of one contact (file comment).
enum class ContactRole : std::uint8_t {
  kUnplanned = 0,  ///< no role stated (plans made before roles were recorded)
  kStick,          ///< `S`
  kSlidePositive,  ///< `+`
  kSlideNegative,  ///< `-`
  kLifted,         ///< `L`
  kFree,           ///< `F`
};

/// \brief Roles of every contact, finger order; entries beyond m are kUnplanned.
using ContactRoles = std::array<ContactRole, kMaxFingers>;

/// \brief +1 / -1 for a planned slide, 0 otherwise.
inline int slipSign(ContactRole r) {
  return r == ContactRole::kSlidePositive ? 1 : r == ContactRole::kSlideNegative ? -1 : 0;
}

/// \brief True when the roles were stated (the first contact's is not kUnplanned).
inline bool planned(const ContactRoles& roles) { return roles[0] != ContactRole::kUnplanned; }

/// \brief The text form of the first m roles (file comment); "" when not planned.
std::string rolesText(const ContactRoles& roles, int m);

/// \brief Parse the text form for m fingers. \throws InputError naming `what` when the
///        text has another length or a letter other than S, +, -, L, F.
ContactRoles parseRoles(std::string_view text, int m, const std::string& what);

/// \brief The role a simulator step gave a contact: separated is lifted; touching with
///        less than `min_force` [N] is free; sticking sticks; sliding slides the way it
///        slipped.
ContactRole roleOf(const ContactStepReport& contact, double min_force);

/// \brief The roles most steps of a stretch gave each contact: `counts[i][r]` counts role
///        r (ContactRole's value) of contact i; ties go to the lower value.
using RoleCounts = std::array<std::array<int, 6>, kMaxFingers>;
ContactRoles majorityRoles(const RoleCounts& counts, int m);

}  // namespace rbsf
