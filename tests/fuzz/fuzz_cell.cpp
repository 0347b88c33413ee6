// libFuzzer target: the cell loader (parseCell from YAML text) and the model built from
// what it accepts. Bad input must end in rbsf::InputError; any other exception, a crash or
// a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/io/cell_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const rbsf::RbsfModel model(rbsf::parseCell(text, "<fuzz>"));
    (void)model.numFingers();
  } catch (const rbsf::InputError&) {
  }
  return 0;
}
