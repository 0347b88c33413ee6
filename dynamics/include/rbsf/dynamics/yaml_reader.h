#pragma once
/// \file
/// \brief The strict reader of the project's YAML input files (the cell, the problem
///        suites): known keys only, no duplicates, typed and finite values, and every
///        message "<label>: <key path> ..." with the key path as written in the file
///        (`fingers[1].stroke[0]`, `problems[2].goal`). InputChecker holds the range checks
///        that code-built values share (Cell::validate()).

#include <cmath>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <yaml-cpp/yaml.h>

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

/// \brief Structural reading of YAML nodes with key-path messages (file comment).
struct YamlReader : InputChecker {
  /// \brief `path`.`key`, or `key` at the root.
  static std::string join(const std::string& path, const std::string& key);
  /// \brief How a node reads in a message: "an empty value", "a list", "a mapping", 'text'.
  static std::string describe(const YAML::Node& n);

  /// \brief The document of `text`; fails with the line and column of a syntax error.
  YAML::Node load(const std::string& text) const;
  /// \brief Requires `n` to be a mapping whose keys are unique and all in `allowed`;
  ///        `what` names the root ("the cell") when `path` is empty.
  void mapping(const YAML::Node& n, const std::string& path,
               std::initializer_list<std::string_view> allowed,
               const std::string& what = "the file") const;
  /// \brief The value at map[key]; fails when missing and required.
  YAML::Node get(const YAML::Node& map, const std::string& path, const char* key,
                 bool required = true) const;
  /// \brief A finite number.
  double number(const YAML::Node& n, const std::string& path) const;
  /// \brief The number at map[key]; `fallback` when missing and not required.
  double number(const YAML::Node& map, const std::string& path, const char* key,
                double fallback = 0, bool required = true) const;
  /// \brief A list of exactly two numbers; `fallback` when missing and not required.
  std::pair<double, double> pair(const YAML::Node& map, const std::string& path, const char* key,
                                 bool required = true,
                                 std::pair<double, double> fallback = {0.0, 0.0}) const;
  /// \brief A plain value (not a list or mapping) as text.
  std::string text(const YAML::Node& n, const std::string& path) const;
};

}  // namespace rbsf
