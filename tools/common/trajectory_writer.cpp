/// \file
/// \brief Trajectory output (see trajectory_writer.h).

#include "rbsf/tools/trajectory_writer.h"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "rbsf/dynamics/atomic_file.h"
#include "rbsf/dynamics/errors.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/tool_main.h"

namespace rbsf::tools {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() > suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

TrajectoryWriter::TrajectoryWriter(std::string path, int m, const std::string& what)
    : path_(std::move(path)), m_(m) {
  const std::string ext = lower(path_);
  if (endsWith(ext, ".csv")) {
    format_ = Format::kCsv;
  } else if (endsWith(ext, ".json")) {
    format_ = Format::kJson;
  } else {
    throw InputError(what + ": '" + path_ + "' must end in .csv or .json (the output format)");
  }
}

void TrajectoryWriter::writeJson(std::ostream& out) const {
  nlohmann::json samples = nlohmann::json::array();
  for (const TrajectorySample& s : samples_) {
    samples.push_back({{"t", s.t},
                       {"q", vectorJson(s.q)},
                       {"v", vectorJson(s.v)},
                       {"tau", vectorJson(s.tau)},
                       {"f_n", vectorJson(s.f_n)},
                       {"phase", std::string(toString(s.phase))}});
  }
  const nlohmann::json doc = {{"columns",
                               {{"t", "time at the end of the step [s]"},
                                {"q", configLayout(m_, false) + " [m, rad]"},
                                {"v", configLayout(m_, true) + " [m/s, rad/s]"},
                                {"tau", "tau_theta [N m], tau_1..tau_m [N], held over the step"},
                                {"f_n", "normal force per contact over the step [N]"},
                                {"phase", "C, P, U or unsupported (MODEL.md)"}}},
                              {"fingers", m_},
                              {"samples", samples}};
  requireFinite(doc, "trajectory");
  out << doc.dump(1) << "\n";
}

void TrajectoryWriter::commit() const {
  // Format everything first (a non-finite value stops here, before any file exists).
  std::ostringstream text;
  if (format_ == Format::kCsv) {
    text << trajectoryCsvText(samples_, m_);
  } else {
    writeJson(text);
  }
  writeFileAtomically(path_, text.str(), "--out");
}

}  // namespace rbsf::tools
