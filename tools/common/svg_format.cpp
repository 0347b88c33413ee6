/// \file
/// \brief Text helpers for the SVG and HTML writers (see svg_format.h).

#include "rbsf/tools/svg_format.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rbsf::tools {

std::string fixedNumber(double x, int decimals) {
  if (!std::isfinite(x)) throw std::runtime_error("picture holds a NaN or infinite value");
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  std::string s(buf);
  // A tiny negative value prints as "-0.00"; the sign would make equal frames differ.
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

std::string escapeXml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

const char* phaseColor(Phase phase) {
  switch (phase) {
    case Phase::kC:
      return "#d4efdf";
    case Phase::kP:
      return "#fae5d3";
    case Phase::kU:
      return "#d6eaf8";
    case Phase::kUnsupported:
      break;
  }
  return "#e5e7e9";
}

const char* phaseDescription(Phase phase) {
  switch (phase) {
    case Phase::kC:
      return "C: every contact sticks";
    case Phase::kP:
      return "P: the part pivots about one contact";
    case Phase::kU:
      return "U: every contact slides";
    case Phase::kUnsupported:
      break;
  }
  return "unsupported: no contact touches";
}

}  // namespace rbsf::tools
