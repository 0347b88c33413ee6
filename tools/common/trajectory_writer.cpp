/// \file
/// \brief Trajectory output (see trajectory_writer.h).

#include "rbsf/tools/trajectory_writer.h"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/atomic_file.h"
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

TrajectoryWriter::TrajectoryWriter(std::string path, int m, const std::string& what,
                                   std::size_t max_samples)
    : path_(std::move(path)), what_(what), m_(m), max_samples_(max_samples) {
  const std::string ext = lower(path_);
  if (endsWith(ext, ".csv")) {
    format_ = Format::kCsv;
  } else if (endsWith(ext, ".json")) {
    format_ = Format::kJson;
  } else {
    throw InputError(what + ": '" + path_ + "' must end in .csv or .json (the output format)");
  }
}

TrajectoryWriter::~TrajectoryWriter() {
  if (file_ == nullptr) return;
  std::fclose(file_);
  std::remove(tmp_.c_str());
}

void TrajectoryWriter::put(const std::string& text) {
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw InputError(what_ + ": cannot write '" + path_ + "'");
}

void TrajectoryWriter::open() {
  tmp_ = temporaryPathFor(path_);
  file_ = std::fopen(tmp_.c_str(), "wb");
  if (file_ == nullptr) throw InputError(what_ + ": cannot write '" + path_ + "'");
  if (format_ == Format::kCsv) {
    put(trajectoryCsvHeader(m_) + "\n");
    return;
  }
  const nlohmann::json columns = {{"t", "time at the end of the step [s]"},
                                  {"q", configLayout(m_, false) + " [m, rad]"},
                                  {"v", configLayout(m_, true) + " [m/s, rad/s]"},
                                  {"tau", "tau_theta [N m], tau_1..tau_m [N], held over the step"},
                                  {"f_n", "normal force per contact over the step [N]"},
                                  {"phase", "C, P, U or unsupported (docs/model.md)"}};
  put("{\"columns\": " + columns.dump() + ",\n \"fingers\": " + std::to_string(m_) +
      ",\n \"samples\": [");
}

void TrajectoryWriter::add(const TrajectorySample& s) {
  if (count_ >= max_samples_)
    throw InputError(what_ + ": more than " + std::to_string(max_samples_) +
                     " samples (one per simulator step); shorten the run or take a larger "
                     "time step");
  if (file_ == nullptr) open();
  line_.clear();
  if (format_ == Format::kCsv) {
    appendTrajectoryCsvRow(line_, s, m_);
  } else {
    const nlohmann::json j = {{"t", s.t},
                              {"q", vectorJson(s.q)},
                              {"v", vectorJson(s.v)},
                              {"tau", vectorJson(s.tau)},
                              {"f_n", vectorJson(s.f_n)},
                              {"phase", std::string(toString(s.phase))}};
    requireFinite(j, "trajectory");
    line_ = (count_ == 0 ? "\n  " : ",\n  ") + j.dump();
  }
  put(line_);
  ++count_;
}

void TrajectoryWriter::commit() {
  if (file_ == nullptr) open();  // no samples: a valid, empty document
  if (format_ == Format::kJson) put("\n ]}\n");
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    std::remove(tmp_.c_str());
    throw InputError(what_ + ": cannot write '" + path_ + "'");
  }
  moveIntoPlace(tmp_, path_, what_);
}

}  // namespace rbsf::tools
