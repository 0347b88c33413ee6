#pragma once
/// \file
/// \brief Sampled trajectories written as CSV or JSON, atomically.
///
/// Samples and the CSV columns are those of rbsf/dynamics/trajectory_sample.h (the plan
/// files' CSV is the same). JSON: {"columns": {...}, "fingers": m, "samples": [{"t": ..,
/// "q": [..], "v": [..], "tau": [..], "f_n": [..], "phase": ".."}, ..]}. The file is written
/// to a temporary name in the same directory and renamed into place, so a failed run never
/// leaves a partial file.

#include <string>
#include <vector>

#include "rbsf/dynamics/trajectory_sample.h"

namespace rbsf::tools {

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

 private:
  void writeJson(std::ostream& out) const;

  std::string path_;
  int m_;
  Format format_;
  std::vector<TrajectorySample> samples_;
};

}  // namespace rbsf::tools
