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

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf::tools {

/// \brief A finite number.
double parseNumber(std::string_view text, std::string_view what);

/// \brief An integer in [lo, hi] (|lo|, |hi| <= 2^53): "<what>: must be an integer in
///        lo..hi (got <text>)" otherwise.
long long parseInteger(std::string_view text, std::string_view what, long long lo, long long hi);

/// \brief The largest |angle| accepted [rad]: 100 turns.
inline constexpr double kMaxAngle = 200.0 * 3.14159265358979323846;
/// \brief The largest |speed| accepted in a velocity [m/s or rad/s].
inline constexpr double kMaxSpeed = 100.0;

/// \brief An angle in radians: "1.2" (radians), "1.2rad" or "30deg" (converted); at most
///        kMaxAngle in magnitude.
double parseAngle(std::string_view text, std::string_view what);

/// \brief Exactly `expected_size` comma-separated numbers. `layout` (e.g.
///        "x,y,phi,theta,l1..l3") is quoted in the length error when given.
std::vector<double> parseVector(std::string_view text, std::string_view what,
                                std::size_t expected_size, std::string_view layout = {});

/// \brief One or more comma-separated numbers.
std::vector<double> parseList(std::string_view text, std::string_view what);

/// \brief Exactly `expected_size` comma-separated, trimmed, non-empty entries, unparsed: for
///        values whose entries are of different kinds (an angle and a length). `layout` is
///        quoted in the length error as in parseVector().
std::vector<std::string_view> parseFields(std::string_view text, std::string_view what,
                                          std::size_t expected_size, std::string_view layout = {});

/// \brief "x,y,phi" with phi an angle (deg suffix allowed).
rbsf::Pose parsePose(std::string_view text, std::string_view what);

/// \brief A configuration q = (x, y, phi, theta, l_1..l_m) in the order of
///        rbsf/dynamics/core/state_layout.h; phi and theta accept the deg suffix.
/// \throws InputError also when m is outside 1..kMaxFingers.
VecQ parseConfig(std::string_view text, std::string_view what, int m);

/// \brief A velocity v = dq/dt (same order as q), plain numbers in SI units (rad/s for
///        the angular rates), each at most kMaxSpeed in magnitude.
VecQ parseVelocity(std::string_view text, std::string_view what, int m);

/// \brief A number for a message, with 6 significant digits ("1e-300", "0.001", "250").
std::string numberText(double x);

/// \brief Inputs within the cell's limits: |tau_theta| <= the base torque limit and
///        |tau_i| <= finger i's force limit.
/// \throws InputError "<where>'tau_2': 250 N exceeds finger 2's force limit 200 N".
void checkInputLimits(const Cell& cell, const VecU& tau, const std::string& where);

/// \brief The layout description used in length errors: "x,y,phi,theta,l1..l3" for a
///        configuration, "dx,dy,dphi,dtheta,dl1..dl3" for a velocity.
std::string configLayout(int m, bool velocity = false);

}  // namespace rbsf::tools
