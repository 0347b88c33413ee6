#pragma once
/// \file
/// \brief The strict reader of the project's YAML input files (the cell, the problem
///        suites): known keys only, no duplicates, typed and finite values, and every
///        message "<label>: <key path> ..." with the key path as written in the file
///        (`fingers[1].stroke[0]`, `problems[2].goal`). Its range checks are
///        InputChecker's (core/input_checks.h), which code-built values share.

#include <cmath>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "rbsf/dynamics/core/input_checks.h"

namespace rbsf {

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
