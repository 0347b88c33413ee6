#pragma once
/// \file
/// \brief SIGINT and SIGTERM as a request to stop: the first signal sets a flag that long
///        searches poll (planner::RunContext::cancel, handed to every stage), so the tool can
///        write its best result so far and exit with exitStatus() (130 for SIGINT, 143 for
///        SIGTERM); a second signal ends the process at once with 128 + its number, writing
///        nothing more.
///
/// The handler is installed with sigaction and does only async-signal-safe work: a
/// lock-free atomic store, and _exit() on the second signal.

#include <atomic>

namespace rbsf::tools {

/// \brief Exit status of a run stopped by SIGINT: 128 + SIGINT, the shell's convention.
inline constexpr int kExitInterrupted = 130;
/// \brief Exit status of a run stopped by SIGTERM: 128 + SIGTERM.
inline constexpr int kExitTerminated = 143;

/// \brief Installs the SIGINT handler for the process lifetime (idempotent) and gives
///        access to its flag. Not a class with state of its own: the handler can only
///        reach a global, so this is a thin interface over it.
class InterruptFlag {
 public:
  /// \brief Install the handler (once) and return the flag it sets.
  /// \throws std::runtime_error if sigaction fails.
  static const std::atomic<bool>& install();

  /// \brief True once a SIGINT or SIGTERM has arrived since install() (or the last reset()).
  static bool raised();

  /// \brief The exit status of a stopped run: kExitTerminated when the first stop request
  ///        was SIGTERM, else kExitInterrupted.
  static int exitStatus();

  /// \brief Clear the flag and the count (tests; a tool never needs this).
  static void reset();
};

}  // namespace rbsf::tools
