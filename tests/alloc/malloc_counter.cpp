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
namespace {
void countOne() {
  if (g_counting.load(std::memory_order_relaxed) > 0) {
    g_mallocs.fetch_add(1, std::memory_order_relaxed);
  }
}
}  // namespace

extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) noexcept {
  countOne();
  return __libc_malloc(size);
}
// GCC turns a malloc followed by a zeroing memset (Eigen's setZero() on a fresh dynamic
// matrix) into calloc; a resize may reach realloc.
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* calloc(std::size_t count, std::size_t size) noexcept {
  countOne();
  return __libc_calloc(count, size);
}
extern "C" void* __libc_realloc(void* pointer, std::size_t size);
extern "C" void* realloc(void* pointer, std::size_t size) noexcept {
  countOne();
  return __libc_realloc(pointer, size);
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
