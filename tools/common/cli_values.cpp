/// \file
/// \brief Strict command-line value parsers (see cli_values.h).

#include "rbsf/tools/cli_values.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <system_error>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::tools {
namespace {

constexpr std::string_view kNotNumber = "is not a number";
constexpr std::string_view kNotAngle = "is not an angle (radians, or degrees with a deg suffix)";

std::string_view trim(std::string_view s) {
  constexpr std::string_view ws = " \t\n\r\f\v";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(ws) - b + 1);
}

[[noreturn]] void fail(std::string_view what, std::string_view msg) {
  throw InputError(std::string(what) + ": " + std::string(msg));
}

[[noreturn]] void failValue(std::string_view what, std::string_view text, std::string_view why) {
  fail(what, "'" + std::string(text) + "' " + std::string(why));
}

/// Parses a trimmed, non-empty number; returns an error phrase or empty on success.
std::string_view scan(std::string_view t, std::string_view syntax_error, double& v) {
  std::string_view body = t;
  if (body.front() == '+') {  // from_chars takes '-' but not '+'
    body.remove_prefix(1);
    if (body.empty() || body.front() == '+' || body.front() == '-') return syntax_error;
  }
  const char* end = body.data() + body.size();
  const auto [ptr, ec] = std::from_chars(body.data(), end, v);
  if (ec == std::errc::result_out_of_range) return "is out of range";
  if (ec != std::errc() || ptr != end) return syntax_error;
  if (!std::isfinite(v)) return "is not finite";
  return {};
}

double number(std::string_view text, std::string_view what) {
  const std::string_view t = trim(text);
  if (t.empty()) fail(what, "empty value (expected a number)");
  double v = 0;
  if (auto err = scan(t, kNotNumber, v); !err.empty()) failValue(what, t, err);
  return v;
}

double angle(std::string_view text, std::string_view what) {
  const std::string_view t = trim(text);
  if (t.empty()) fail(what, "empty value (expected an angle)");
  std::string_view body = t;
  double scale = 1.0;
  if (body.ends_with("deg")) {
    body.remove_suffix(3);
    scale = std::numbers::pi / 180.0;
  } else if (body.ends_with("rad")) {
    body.remove_suffix(3);
  }
  body = trim(body);
  double v = 0;
  if (body.empty()) failValue(what, t, kNotAngle);
  if (auto err = scan(body, kNotAngle, v); !err.empty()) failValue(what, t, err);
  if (!(std::abs(v * scale) <= kMaxAngle))
    failValue(what, t, "is beyond +-36000 deg (100 turns), the largest angle accepted");
  return v * scale;
}

/// Splits "a, b, c" into exactly `expected` trimmed, non-empty entries (any number of them
/// for kAnyCount).
constexpr std::size_t kAnyCount = 0;
std::vector<std::string_view> split(std::string_view text, std::string_view what,
                                    std::size_t expected, std::string_view layout) {
  const std::string want = (expected == kAnyCount ? "one or more numbers"
                                                  : std::to_string(expected) +
                                                        (expected == 1 ? " number" : " numbers")) +
                           (layout.empty() ? "" : " (" + std::string(layout) + ")");
  if (trim(text).empty()) fail(what, "empty value (expected " + want + ")");
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = text.find(',', start);
    const std::string_view tok = trim(text.substr(start, comma - start));
    if (tok.empty())
      fail(what, "entry " + std::to_string(out.size() + 1) + " is empty (stray comma?)");
    out.push_back(tok);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (expected != kAnyCount && out.size() != expected)
    fail(what, "expected " + want + ", got " + std::to_string(out.size()));
  return out;
}

std::string entryWhat(std::string_view what, std::size_t i, std::string_view name = {}) {
  return std::string(what) + " entry " + std::to_string(i + 1) +
         (name.empty() ? "" : " (" + std::string(name) + ")");
}

/// Each entry as a number, named by its place in `what`.
std::vector<double> numbers(const std::vector<std::string_view>& tokens, std::string_view what) {
  std::vector<double> out;
  out.reserve(tokens.size());
  for (std::size_t i = 0; i < tokens.size(); ++i)
    out.push_back(number(tokens[i], entryWhat(what, i)));
  return out;
}

/// Name of configuration (or velocity) entry i, e.g. "phi", "l2", "dtheta".
std::string entryName(int i, bool velocity) {
  std::string name = velocity ? "d" : "";
  switch (i) {
    case layout::kX:
      name += "x";
      break;
    case layout::kY:
      name += "y";
      break;
    case layout::kPhi:
      name += "phi";
      break;
    case layout::kTheta:
      name += "theta";
      break;
    default:
      name += "l";
      name += std::to_string(i - layout::kFirstStroke + 1);
      break;
  }
  return name;
}

VecQ parseState(std::string_view text, std::string_view what, int m, bool velocity) {
  if (m < 1 || m > kMaxFingers)
    fail(what,
         "finger count " + std::to_string(m) + " is outside 1.." + std::to_string(kMaxFingers));
  const int n = layout::configDim(m);
  const auto tokens = split(text, what, static_cast<std::size_t>(n), configLayout(m, velocity));
  VecQ q(n);
  for (int i = 0; i < n; ++i) {
    const std::string w = entryWhat(what, static_cast<std::size_t>(i), entryName(i, velocity));
    const bool is_angle = !velocity && (i == layout::kPhi || i == layout::kTheta);
    q[i] = is_angle ? angle(tokens[i], w) : number(tokens[i], w);
    if (velocity && !(std::abs(q[i]) <= kMaxSpeed))
      failValue(w, tokens[i], "is beyond 100 (m/s or rad/s), the largest speed accepted");
  }
  return q;
}

}  // namespace

double parseNumber(std::string_view text, std::string_view what) { return number(text, what); }

long long parseInteger(std::string_view text, std::string_view what, long long lo, long long hi) {
  const double v = number(text, what);
  if (!(v >= static_cast<double>(lo) && v <= static_cast<double>(hi) && v == std::floor(v)))
    throw InputError(std::string(what) + ": must be an integer in " + std::to_string(lo) + ".." +
                     std::to_string(hi) + " (got " + std::string(text) + ")");
  return static_cast<long long>(v);
}

double parseAngle(std::string_view text, std::string_view what) { return angle(text, what); }

std::vector<double> parseVector(std::string_view text, std::string_view what,
                                std::size_t expected_size, std::string_view layout) {
  return numbers(split(text, what, expected_size, layout), what);
}

std::vector<double> parseList(std::string_view text, std::string_view what) {
  return numbers(split(text, what, kAnyCount, {}), what);
}

std::vector<std::string_view> parseFields(std::string_view text, std::string_view what,
                                          std::size_t expected_size, std::string_view layout) {
  return split(text, what, expected_size, layout);
}

rbsf::Pose parsePose(std::string_view text, std::string_view what) {
  const auto tokens = split(text, what, layout::kObjectDim, "x,y,phi");
  rbsf::Pose p;
  p.x = number(tokens[layout::kX], entryWhat(what, layout::kX, "x"));
  p.y = number(tokens[layout::kY], entryWhat(what, layout::kY, "y"));
  p.phi = angle(tokens[layout::kPhi], entryWhat(what, layout::kPhi, "phi"));
  return p;
}

VecQ parseConfig(std::string_view text, std::string_view what, int m) {
  return parseState(text, what, m, false);
}

VecQ parseVelocity(std::string_view text, std::string_view what, int m) {
  return parseState(text, what, m, true);
}

std::string configLayout(int m, bool velocity) {
  std::string out;
  for (int i = 0; i < layout::kFirstStroke; ++i) out += entryName(i, velocity) + ",";
  const std::string d = velocity ? "d" : "";
  if (m >= 3) return out + d + "l1.." + d + "l" + std::to_string(m);
  for (int i = 0; i < m; ++i)
    out += entryName(layout::stroke(i), velocity) + (i + 1 < m ? "," : "");
  return out;
}

std::string numberText(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

void checkInputLimits(const Cell& cell, const VecU& tau, const std::string& where) {
  const auto text = numberText;
  if (!(std::abs(tau[layout::kTauTheta]) <= cell.base.torque_limit))
    throw InputError(where + "'tau_theta': " + text(tau[layout::kTauTheta]) +
                     " N m exceeds the base torque limit " + text(cell.base.torque_limit) + " N m");
  for (std::size_t i = 0; i < cell.fingers.size(); ++i) {
    const double f = tau[layout::fingerForce(static_cast<int>(i))];
    if (!(std::abs(f) <= cell.fingers[i].force_limit))
      throw InputError(where + "'tau_" + std::to_string(i + 1) + "': " + text(f) +
                       " N exceeds finger " + std::to_string(i + 1) + "'s force limit " +
                       text(cell.fingers[i].force_limit) + " N");
  }
}

}  // namespace rbsf::tools
