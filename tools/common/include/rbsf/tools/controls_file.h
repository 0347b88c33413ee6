#pragma once
/// \file
/// \brief Piecewise-constant input schedules ("controls files") for the tools.
///
/// Format (CSV, one header line, then one segment per line):
///
///     duration,tau_theta,tau_1,tau_2,tau_3
///     1.0,23.5,39.8,98.0,156.4
///     0.5,43.5,39.8,98.0,156.4
///
/// - the header names exactly the columns duration, tau_theta, tau_1 .. tau_m for the
///   cell's m fingers (state_layout.h order of tau);
/// - duration [s] > 0; tau_theta [N m], tau_i [N], all finite numbers (cli_values rules:
///   decimal or scientific, surrounding blanks ignored);
/// - blank lines and lines starting with '#' are ignored; CRLF line ends are accepted;
/// - at least one segment.
/// Every error is an InputError whose message names the file, the line and the column,
/// e.g. "ctl.csv:4: column 'tau_2': 'abc' is not a number".

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace rbsf::tools {

/// \brief One line of a controls file: tau held for `duration` seconds.
struct ControlSegment {
  double duration = 0.0;  ///< [s]
  Eigen::VectorXd tau;    ///< (tau_theta, tau_1..tau_m)
  int line = 0;           ///< 1-based line in the file, for messages
};

/// \brief A parsed controls file.
class ControlSchedule {
 public:
  /// \brief Read `path` for a cell with m fingers.
  /// \throws InputError for a missing/unreadable file or any format error.
  static ControlSchedule load(const std::string& path, int m);

  /// \brief Parse CSV text; `label` names the source in messages.
  static ControlSchedule parse(std::string_view text, int m, const std::string& label);

  /// \brief The expected header, "duration,tau_theta,tau_1,...,tau_m".
  static std::string header(int m);

  const std::vector<ControlSegment>& segments() const { return segments_; }
  const std::string& label() const { return label_; }
  /// \brief Sum of the durations [s].
  double totalDuration() const;

 private:
  std::string label_;
  std::vector<ControlSegment> segments_;
};

}  // namespace rbsf::tools
