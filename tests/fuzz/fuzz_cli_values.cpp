// libFuzzer target: the command-line value parsers of tools/common/cli_values.h. The first
// byte picks the parser (and a size), the rest is the text. Bad text must end in
// rbsf::InputError; anything else, and any accepted non-finite value, is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/tools/cli_values.h"

namespace {

void requireFinite(double x) {
  if (!std::isfinite(x)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  const int selector = data[0] % 6, n = data[0] / 6;  // n in 0..42
  using namespace rbsf::tools;
  try {
    switch (selector) {
      case 0:
        requireFinite(parseNumber(text, "--x"));
        break;
      case 1:
        requireFinite(parseAngle(text, "--x"));
        break;
      case 2:  // a size of 0: a list of any length; else exactly that many
        try {  // the same text split unparsed: entries are never empty nor hold a comma
          for (const std::string_view f : parseFields(text, "--x", 1 + n % 4))
            if (f.empty() || f.find(',') != std::string_view::npos) std::abort();
        } catch (const rbsf::InputError&) {
        }
        for (const double x : n % 16 == 0
                                  ? parseList(text, "--x")
                                  : parseVector(text, "--x", static_cast<std::size_t>(n % 16)))
          requireFinite(x);
        break;
      case 3: {
        const rbsf::Pose p = parsePose(text, "--x");
        requireFinite(p.x), requireFinite(p.y), requireFinite(p.phi);
        break;
      }
      case 4:
        if (!parseConfig(text, "--x", n % 16 - 1).allFinite()) std::abort();
        break;
      default:
        if (!parseVelocity(text, "--x", n % 16 - 1).allFinite()) std::abort();
        break;
    }
  } catch (const rbsf::InputError&) {
  }
  return 0;
}
