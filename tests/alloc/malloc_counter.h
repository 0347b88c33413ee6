#pragma once
// Counts heap allocations in this test binary. Eigen allocates through malloc, not
// operator new, so malloc itself is interposed (glibc lets the executable do that), and with
// it calloc and realloc.
// Sanitizers interpose malloc themselves: there counting is unavailable and the tests skip.

namespace rbsf::test {

/// \brief True when this build can count mallocs.
bool mallocCountingAvailable();

/// \brief Counts the mallocs made between construction and count().
class MallocCounter {
 public:
  MallocCounter();
  ~MallocCounter();
  long count() const;

 private:
  long start_;
};

}  // namespace rbsf::test
