#pragma once
/// \file
/// \brief The files of one tool run, checked together before any work: no output may
///        destroy an input, another output or something that is not a file.
///
/// An output is refused (InputError naming its option, exit status 2) when
///   - it is one of the run's inputs or another output: the same file by device and inode
///     when it exists, else the same resolved directory and name (so `o/./p.json`,
///     `o//p.json` and a path through a symbolic link to `o` are all `o/p.json`);
///   - it exists and is not a regular file (a device such as /dev/null, a FIFO, a
///     directory, or a symbolic link, which the atomic rename would replace instead of its
///     target);
///   - its directory cannot take a new file (checkWritable, atomic_file.h: a temporary file
///     is created there and removed).
/// Inputs are read later with readInputFile (input_file.h).

#include <string>
#include <vector>

namespace rbsf::tools {

/// \brief Inputs and outputs of one run (file comment).
class RunFiles {
 public:
  /// \brief Record an input given to `option` (a missing input is refused when it is read).
  void addInput(const std::string& path, const std::string& option);
  /// \brief Check and record an output given to `option`; an empty path is ignored.
  /// \throws InputError as the file comment says.
  void addOutput(const std::string& path, const std::string& option);

 private:
  struct Entry {
    std::string path, option, resolved;  ///< resolved: directory made absolute, then the name
    bool exists = false;
    unsigned long long device = 0, inode = 0;
  };
  static Entry identify(const std::string& path, const std::string& option, bool follow);
  static bool same(const Entry& a, const Entry& b);
  std::vector<Entry> inputs_, outputs_;
};

}  // namespace rbsf::tools
