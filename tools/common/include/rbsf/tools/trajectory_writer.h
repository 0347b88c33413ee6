#pragma once
/// \file
/// \brief Sampled trajectories written as CSV or JSON, atomically.
///
/// A sample is the state (t, q, v) at the end of a simulator step together with the input
/// tau, the normal forces f_n per contact and the phase of that step. Columns, in order
/// (state_layout.h for q, v and tau; contacts in finger order):
///
///     t, x, y, phi, theta, l1..lm, dx, dy, dphi, dtheta, dl1..dlm,
///     tau_theta, tau_1..tau_m, fn_1..fn_m, phase
///
/// SI units, radians; phase is C, P, U or unsupported. CSV: one header line with these
/// names, then one line per sample, numbers with 17 significant digits (round-trip exact).
/// JSON: {"columns": {...}, "samples": [{"t": .., "q": [..], "v": [..], "tau": [..],
/// "f_n": [..], "phase": ".."}, ..]}. The file is written to a temporary name in the same
/// directory and renamed into place, so a failed run never leaves a partial file.

#include <string>
#include <vector>

#include "rbsf/dynamics/phase.h"
#include "rbsf/dynamics/types.h"

namespace rbsf::tools {

/// \brief One sample (see the file comment).
struct TrajectorySample {
  double t = 0.0;
  VecQ q, v;
  VecU tau;
  VecC f_n;
  Phase phase = Phase::kUnsupported;
};

/// \brief Collects samples and writes them in the format of the output file's extension.
class TrajectoryWriter {
 public:
  enum class Format { kCsv, kJson };

  /// \brief Output to `path` (".csv" or ".json", case-insensitive) for m fingers.
  /// \throws InputError naming `what` (the option) for any other extension.
  TrajectoryWriter(std::string path, int m, const std::string& what = "--out");

  Format format() const { return format_; }
  const std::string& path() const { return path_; }
  std::size_t size() const { return samples_.size(); }

  void add(const TrajectorySample& sample) { samples_.push_back(sample); }

  /// \brief Write every sample to a temporary file and rename it to path().
  /// \throws InputError when the directory is not writable (the message names the path).
  void commit() const;

  /// \brief The CSV header line (without newline).
  static std::string csvHeader(int m);

 private:
  void writeCsv(std::ostream& out) const;
  void writeJson(std::ostream& out) const;

  std::string path_;
  int m_;
  Format format_;
  std::vector<TrajectorySample> samples_;
};

}  // namespace rbsf::tools
