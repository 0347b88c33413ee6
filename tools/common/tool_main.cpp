#include "rbsf/tools/tool_main.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::tools {

void parseCommandLine(CLI::App& app, int argc, char** argv) {
  // CLI11 would read "-0.1,0.4" as an unknown short option; a value that looks like a
  // number is glued to its option as "--name=value" so it always parses as a value.
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    const bool numeric_next =
        i + 1 < argc && argv[i + 1][0] == '-' &&
        (std::isdigit(static_cast<unsigned char>(argv[i + 1][1])) || argv[i + 1][1] == '.');
    if (a.rfind("--", 0) == 0 && a.find('=') == std::string::npos && numeric_next) {
      a += "=";
      a += argv[++i];
    }
    args.push_back(std::move(a));
  }
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    throw HelpPrinted{};
  } catch (const CLI::ParseError& e) {
    throw InputError(e.what());
  }
}

int toolMain(const char* name, int argc, char** argv, const std::function<int(int, char**)>& body) {
  try {
    return body(argc, argv);
  } catch (const HelpPrinted&) {
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", name, e.what());
    return kExitInternal;
  }
}

nlohmann::json vectorJson(const Eigen::Ref<const Eigen::VectorXd>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

bool allFinite(const nlohmann::json& j) {
  if (j.is_number_float()) return std::isfinite(j.get<double>());
  if (j.is_structured())
    for (const auto& item : j)
      if (!allFinite(item)) return false;
  return true;
}

void requireFinite(const nlohmann::json& j, const std::string& what) {
  if (!allFinite(j)) throw std::runtime_error(what + " holds a non-finite number");
}

}  // namespace rbsf::tools
