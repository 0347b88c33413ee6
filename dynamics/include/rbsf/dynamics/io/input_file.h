#pragma once
/// \file
/// \brief The one way every tool reads an input file (cell, plan, controls, problem suite,
///        benchmark log): a regular file of at most kMaxInputBytes, read whole. A device,
///        FIFO or directory is refused before a byte is read, so `--cell /dev/zero` stops at
///        once instead of filling memory.

#include <cstddef>
#include <string>

namespace rbsf {

/// \brief The largest input file read [bytes] (64 MiB: a support plan with its samples is
///        about 2 MB, a cell a few kB).
inline constexpr std::size_t kMaxInputBytes = std::size_t{64} << 20;

/// \brief The whole text of the input file at `path`.
/// \throws InputError "<path>: cannot read the <what>: <reason>" when it is missing,
///         unreadable, not a regular file or larger than `max_bytes`.
std::string readInputFile(const std::string& path, const std::string& what,
                          std::size_t max_bytes = kMaxInputBytes);

}  // namespace rbsf
