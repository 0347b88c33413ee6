#include "malloc_counter.h"

#include <atomic>
#include <cstddef>

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define RBSF_COUNT_MALLOC 1
#endif

namespace {
std::atomic<int> g_counting{0};
std::atomic<long> g_mallocs{0};
}  // namespace

#ifdef RBSF_COUNT_MALLOC
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) noexcept {
  if (g_counting.load(std::memory_order_relaxed) > 0) {
    g_mallocs.fetch_add(1, std::memory_order_relaxed);
  }
  return __libc_malloc(size);
}
#endif

namespace rbsf::test {

bool mallocCountingAvailable() {
#ifdef RBSF_COUNT_MALLOC
  return true;
#else
  return false;
#endif
}

MallocCounter::MallocCounter() : start_(g_mallocs.load()) { ++g_counting; }
MallocCounter::~MallocCounter() { --g_counting; }
long MallocCounter::count() const { return g_mallocs.load() - start_; }

}  // namespace rbsf::test
