// libFuzzer target: the problem-suite reader of rbsf-bench (parseProblemSuite), its cells
// resolved against the repository's cells/problems folder so that the seeds' cells load.
// Bad input must end in rbsf::InputError; any other exception, a crash or a sanitizer
// report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "rbsf/bench/problem_suite.h"
#include "rbsf/dynamics/core/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto problems = rbsf::bench::parseProblemSuite(
        text, std::string(RBSF_SOURCE_DIR) + "/cells/problems/fuzz.yaml");
    (void)problems.size();
  } catch (const rbsf::InputError&) {
  }
  return 0;
}
