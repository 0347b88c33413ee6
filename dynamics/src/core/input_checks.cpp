#include "rbsf/dynamics/core/input_checks.h"

#include <charconv>
#include <cmath>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

std::string roundTripText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  auto res = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, res.ptr);
}

std::string messagePrefix(const std::string& label) { return label.empty() ? "" : label + ": "; }

void InputChecker::fail(const std::string& msg) const { throw InputError(prefix + msg); }

void InputChecker::finite(double v, const std::string& path) const {
  if (!std::isfinite(v)) fail(path + " must be a finite number (got " + roundTripText(v) + ")");
}

void InputChecker::positive(double v, const std::string& path) const {
  finite(v, path);
  if (!(v > 0)) fail(path + " must be positive (got " + roundTripText(v) + ")");
}

void InputChecker::nonNegative(double v, const std::string& path) const {
  finite(v, path);
  if (v < 0) fail(path + " must not be negative (got " + roundTripText(v) + ")");
}

void InputChecker::interval(double lo, double hi, const std::string& path) const {
  finite(lo, path + "[0]");
  finite(hi, path + "[1]");
  if (!(lo < hi))
    fail(path + " must be [lo, hi] with lo < hi (got [" + roundTripText(lo) + ", " +
         roundTripText(hi) + "])");
}

void InputChecker::atMost(double v, double max, const std::string& max_text,
                          const std::string& path) const {
  if (v > max) fail(path + " must be at most " + max_text + " (got " + roundTripText(v) + ")");
}

void InputChecker::fraction(double v, const std::string& path) const {
  finite(v, path);
  if (!(v >= 0 && v < 1)) fail(path + " must lie in [0, 1) (got " + roundTripText(v) + ")");
}

}  // namespace rbsf
