#pragma once
/// \file
/// \brief Range checks of input values with messages that name the key path, shared by
///        values read from files (io/yaml_reader.h) and built in code (Cell::validate()).

#include <string>

namespace rbsf {

/// \brief Shortest round-trip text of a number ("-2", "0.1", "nan").
std::string roundTripText(double v);

/// \brief "<label>: ", or nothing for an empty label.
std::string messagePrefix(const std::string& label);

/// \brief Range checks with messages "<prefix><path> must be ... (got v)"; each throws
///        InputError.
struct InputChecker {
  std::string prefix;

  [[noreturn]] void fail(const std::string& msg) const;
  void finite(double v, const std::string& path) const;
  void positive(double v, const std::string& path) const;
  void nonNegative(double v, const std::string& path) const;
  /// \brief [lo, hi] with lo < hi, both finite.
  void interval(double lo, double hi, const std::string& path) const;
  /// \brief v <= max; `max_text` is the bound as the message shows it ("10000 Hz", "pi/4").
  void atMost(double v, double max, const std::string& max_text, const std::string& path) const;
  /// \brief A relative half-width: 0 <= v < 1, so a draw keeps the quantity positive.
  void fraction(double v, const std::string& path) const;
};

}  // namespace rbsf
