// libFuzzer target: the plan-file loader (parsePlanJson, what readPlanJson reads files
// with). A malformed plan must end in rbsf::InputError; anything else is a bug. Accepted
// plans are written back and must read again.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/plan/plan_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rbsf::plan::PlanRecord plan;
  try {
    plan = rbsf::plan::parsePlanJson(text, "<fuzz>");
  } catch (const rbsf::InputError&) {
    return 0;
  }
  // What was accepted is finite (writers refuse NaN) or refused by the writer; a written
  // plan reads back.
  std::string again;
  try {
    again = rbsf::plan::planJsonText(plan);
  } catch (const std::runtime_error&) {
    return 0;
  }
  (void)rbsf::plan::parsePlanJson(again, "<fuzz: written back>");
  return 0;
}
