#pragma once
/// \file
/// \brief Output files that are complete or absent: text written to a temporary name in
///        the target's directory, flushed, then renamed into place (rename(2) is atomic
///        within one file system, so a reader sees the old file or the whole new one).
///        Plan files, trajectories, pictures and benchmark logs are all written this way.

#include <string>
#include <string_view>

namespace rbsf {

/// \brief The temporary name used for `path` by writeFileAtomically():
///        "<path>.tmp.<pid>" (the pid keeps concurrent runs apart).
std::string temporaryPathFor(const std::string& path);

/// \brief The directory part of `path` as written: "." for a bare name, "/" for a file
///        in the root (not resolved; links and "." are left as they are).
std::string directoryOf(const std::string& path);

/// \brief Write `text` to `path` atomically (see the file comment). Only a regular file is
///        ever replaced: an existing device, FIFO, directory or symbolic link at `path` is
///        refused. On any failure the temporary file is removed and `path` is left as it was.
/// \throws InputError "<what>: cannot write '<path>'" when the file cannot be created,
///         written or moved into place (a missing or read-only directory is bad input).
void writeFileAtomically(const std::string& path, std::string_view text, const std::string& what);

/// \brief Rename the finished temporary file `tmp` to `path` under writeFileAtomically()'s
///        rules (only a regular file is replaced); on failure `tmp` is removed.
/// \throws InputError naming `what` and `path`.
void moveIntoPlace(const std::string& tmp, const std::string& path, const std::string& what);

/// \brief Check before any work that `path` can be written: its directory exists and takes
///        a new file (one is created there and removed), and `path` is absent or a regular
///        file (not a directory, device, FIFO or symbolic link).
/// \throws InputError "<what>: cannot write '<path>': <reason>".
void checkWritable(const std::string& path, const std::string& what);

}  // namespace rbsf
