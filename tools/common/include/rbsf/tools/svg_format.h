#pragma once
/// \file
/// \brief Text helpers shared by the SVG and HTML writers: numbers in a fixed, locale-free
///        format (so the same plan gives the same bytes) and XML escaping.

#include <string>
#include <string_view>

#include "rbsf/dynamics/core/phase.h"

namespace rbsf::tools {

/// \brief `x` with `decimals` digits after the point ("%.*f"), "-0.00" folded to "0.00".
/// \throws std::runtime_error for a NaN or an infinity (pictures never carry them).
std::string fixedNumber(double x, int decimals);

/// \brief `text` with &, <, >, " and ' replaced by XML entities.
std::string escapeXml(std::string_view text);

/// \brief Background colour of a phase in the pictures (C green, P orange, U blue,
///        unsupported grey), as "#rrggbb".
const char* phaseColor(Phase phase);

/// \brief One-line description of a phase for labels, e.g. "C: every contact sticks".
const char* phaseDescription(Phase phase);

}  // namespace rbsf::tools
