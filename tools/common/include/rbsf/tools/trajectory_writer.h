#pragma once
/// \file
/// \brief Sampled trajectories written as CSV or JSON, streamed and atomic.
///
/// Samples and the CSV columns are those of rbsf/dynamics/core/trajectory_sample.h (the plan
/// files' CSV is the same). JSON: {"columns": {...}, "fingers": m, "samples": [{"t": ..,
/// "q": [..], "v": [..], "tau": [..], "f_n": [..], "phase": ".."}, ..]}. Each sample goes
/// to a temporary file in the target's directory as it is added (memory stays flat however
/// long the run), and commit() renames it into place (atomic_file.h), so a failed run never
/// leaves a partial file: the temporary file is removed when the writer is destroyed
/// uncommitted. At most max_samples samples are taken.

#include <cstddef>
#include <cstdio>
#include <string>

#include "rbsf/dynamics/core/trajectory_sample.h"

namespace rbsf::tools {

/// \brief Streams samples to a file in the format of its extension.
class TrajectoryWriter {
 public:
  enum class Format { kCsv, kJson };

  /// \brief The default cap on samples: 10^6 (a CSV of about 300 MB with m = 3).
  static constexpr std::size_t kMaxSamples = 1000000;

  /// \brief Output to `path` (".csv" or ".json", case-insensitive) for m fingers.
  /// \throws InputError naming `what` (the option) for any other extension.
  TrajectoryWriter(std::string path, int m, const std::string& what = "--out",
                   std::size_t max_samples = kMaxSamples);
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

  Format format() const { return format_; }
  const std::string& path() const { return path_; }
  std::size_t size() const { return count_; }
  std::size_t maxSamples() const { return max_samples_; }

  /// \brief Append one sample to the temporary file (opened on the first call).
  /// \throws InputError when the file cannot be written or more than maxSamples() samples
  ///         are added; std::runtime_error for a non-finite number.
  void add(const TrajectorySample& sample);

  /// \brief Finish the document and rename it to path().
  /// \throws InputError when it cannot be written or moved into place.
  void commit();

 private:
  void open();
  void put(const std::string& text);

  std::string path_, what_, tmp_;
  int m_;
  Format format_;
  std::size_t max_samples_, count_ = 0;
  std::FILE* file_ = nullptr;
  std::string line_;  ///< one sample's text, reused
};

}  // namespace rbsf::tools
