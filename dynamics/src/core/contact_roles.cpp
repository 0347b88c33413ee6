#include "rbsf/dynamics/core/contact_roles.h"

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

std::string rolesText(const ContactRoles& roles, int m) {
  if (!planned(roles)) return "";
  std::string s;
  for (int i = 0; i < m; ++i) {
    switch (roles[i]) {
      case ContactRole::kStick:
        s += 'S';
        break;
      case ContactRole::kSlidePositive:
        s += '+';
        break;
      case ContactRole::kSlideNegative:
        s += '-';
        break;
      case ContactRole::kLifted:
        s += 'L';
        break;
      case ContactRole::kFree:
        s += 'F';
        break;
      case ContactRole::kUnplanned:
        s += '?';
        break;
    }
  }
  return s;
}

ContactRoles parseRoles(std::string_view text, int m, const std::string& what) {
  ContactRoles roles{};
  if (static_cast<int>(text.size()) != m)
    throw InputError(what + ": expected " + std::to_string(m) +
                     " contact roles (one of S, +, -, L, F per finger), got \"" +
                     std::string(text) + "\"");
  for (int i = 0; i < m; ++i) {
    switch (text[static_cast<std::size_t>(i)]) {
      case 'S':
        roles[i] = ContactRole::kStick;
        break;
      case '+':
        roles[i] = ContactRole::kSlidePositive;
        break;
      case '-':
        roles[i] = ContactRole::kSlideNegative;
        break;
      case 'L':
        roles[i] = ContactRole::kLifted;
        break;
      case 'F':
        roles[i] = ContactRole::kFree;
        break;
      default:
        throw InputError(what + ": contact role '" +
                         std::string(1, text[static_cast<std::size_t>(i)]) + "' of finger " +
                         std::to_string(i + 1) + " is not one of S, +, -, L, F");
    }
  }
  return roles;
}

ContactRole roleOf(const ContactStepReport& c, double min_force) {
  if (c.mode == ContactMode::kSeparated) return ContactRole::kLifted;
  if (!(c.f_n >= min_force)) return ContactRole::kFree;
  if (c.mode == ContactMode::kStick) return ContactRole::kStick;
  return c.slip < 0.0 ? ContactRole::kSlideNegative : ContactRole::kSlidePositive;
}

ContactRoles majorityRoles(const RoleCounts& counts, int m) {
  ContactRoles roles{};
  for (int i = 0; i < m; ++i) {
    int best = 1;
    for (int r = 2; r < 6; ++r)
      if (counts[i][r] > counts[i][best]) best = r;
    roles[i] = static_cast<ContactRole>(best);
  }
  return roles;
}

}  // namespace rbsf
