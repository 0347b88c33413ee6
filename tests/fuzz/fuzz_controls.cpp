// libFuzzer target: the controls-file parser of rbsf-simulate (ControlSchedule::parse) for
// one to four fingers (the first byte picks m). Bad input must end in rbsf::InputError; any
// other exception, a crash or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/tools/controls_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int m = 1 + data[0] % 4;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const rbsf::tools::ControlSchedule s = rbsf::tools::ControlSchedule::parse(text, m, "<fuzz>");
    (void)s.segments().size();
  } catch (const rbsf::InputError&) {
  }
  return 0;
}
