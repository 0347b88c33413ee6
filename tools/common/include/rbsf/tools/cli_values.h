#pragma once
/// \file
/// \brief Strict parsers for values given on the command line (numbers, angles, vectors,
///        poses, configurations, velocities).
///
/// Every parser accepts the whole string or throws rbsf::InputError whose message starts
/// with `what` (the option name, e.g. "--q"):
///   "--v: 'abc' is not a number", "--q: expected 7 numbers (x,y,phi,theta,l1..l3), got 5".
/// Numbers use std::from_chars (decimal or scientific, an optional leading '+'); surrounding
/// whitespace is ignored; empty strings, "nan", "inf" and overflowing values are rejected.
/// Angles are radians unless suffixed "deg" ("30deg", "-45deg"); a "rad" suffix is allowed.
/// Vectors are comma-separated; an empty entry (e.g. a trailing comma) is an error.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "rbsf/dynamics/placement.h"
#include "rbsf/dynamics/types.h"

namespace rbsf::tools {

/// \brief A finite number.
double parseNumber(std::string_view text, std::string_view what);

/// \brief An integer in [lo, hi] (|lo|, |hi| <= 2^53): "<what>: must be an integer in
///        lo..hi (got <text>)" otherwise.
long long parseInteger(std::string_view text, std::string_view what, long long lo, long long hi);

/// \brief An angle in radians: "1.2" (radians), "1.2rad" or "30deg" (converted).
double parseAngle(std::string_view text, std::string_view what);

/// \brief Exactly `expected_size` comma-separated numbers. `layout` (e.g.
///        "x,y,phi,theta,l1..l3") is quoted in the length error when given.
std::vector<double> parseVector(std::string_view text, std::string_view what,
                                std::size_t expected_size, std::string_view layout = {});

/// \brief "x,y,phi" with phi an angle (deg suffix allowed).
rbsf::Pose parsePose(std::string_view text, std::string_view what);

/// \brief A configuration q = (x, y, phi, theta, l_1..l_m) in the order of
///        rbsf/dynamics/state_layout.h; phi and theta accept the deg suffix.
/// \throws InputError also when m is outside 1..kMaxFingers.
VecQ parseConfig(std::string_view text, std::string_view what, int m);

/// \brief A velocity v = dq/dt (same order as q), plain numbers in SI units (rad/s for
///        the angular rates).
VecQ parseVelocity(std::string_view text, std::string_view what, int m);

/// \brief The layout description used in length errors: "x,y,phi,theta,l1..l3" for a
///        configuration, "dx,dy,dphi,dtheta,dl1..dl3" for a velocity.
std::string configLayout(int m, bool velocity = false);

}  // namespace rbsf::tools
