/// \file
/// \brief The SIGINT handler (see interrupt.h).

#include "rbsf/tools/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace rbsf::tools {
namespace {

// Only lock-free atomics may be touched from a signal handler.
static_assert(std::atomic<bool>::is_always_lock_free);
static_assert(std::atomic<int>::is_always_lock_free);

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_count{0};
std::atomic<bool> g_installed{false};
std::atomic<int> g_signal{SIGINT};  // the first stop request's signal

extern "C" void onStop(int sig) {
  if (g_count.fetch_add(1, std::memory_order_relaxed) >= 1) _exit(128 + sig);
  g_signal.store(sig, std::memory_order_relaxed);
  g_interrupted.store(true, std::memory_order_relaxed);
}

}  // namespace

const std::atomic<bool>& InterruptFlag::install() {
  if (!g_installed.exchange(true)) {
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = onStop;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // interrupted reads and writes resume
    if (sigaction(SIGINT, &sa, nullptr) != 0 || sigaction(SIGTERM, &sa, nullptr) != 0) {
      g_installed.store(false);
      throw std::runtime_error(std::string("cannot install the SIGINT/SIGTERM handler: ") +
                               std::strerror(errno));
    }
  }
  return g_interrupted;
}

bool InterruptFlag::raised() { return g_interrupted.load(std::memory_order_relaxed); }

int InterruptFlag::exitStatus() {
  return g_signal.load(std::memory_order_relaxed) == SIGTERM ? kExitTerminated : kExitInterrupted;
}

void InterruptFlag::reset() {
  g_count.store(0);
  g_signal.store(SIGINT);
  g_interrupted.store(false);
}

}  // namespace rbsf::tools
