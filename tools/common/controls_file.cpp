/// \file
/// \brief Controls-file parser (see controls_file.h).

#include "rbsf/tools/controls_file.h"

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/input_file.h"
#include "rbsf/tools/cli_values.h"

namespace rbsf::tools {
namespace {

std::string_view trim(std::string_view s) {
  constexpr std::string_view ws = " \t\r\n\f\v";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(ws) - b + 1);
}

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

std::string columnName(int j) {
  return j == 0 ? "duration" : j == 1 ? "tau_theta" : "tau_" + std::to_string(j - 1);
}

}  // namespace

std::string ControlSchedule::header(int m) {
  std::string h;
  for (int j = 0; j < m + 2; ++j) {
    if (j > 0) h += ',';
    h += columnName(j);
  }
  return h;
}

ControlSchedule ControlSchedule::load(const std::string& path, int m) {
  return parse(readInputFile(path, "controls file"), m, path);
}

ControlSchedule ControlSchedule::parse(std::string_view text, int m, const std::string& label) {
  ControlSchedule s;
  s.label_ = label;
  const int columns = m + 2;
  const std::string expected = header(m);
  bool have_header = false;
  int line_no = 0;
  for (std::size_t start = 0; start <= text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = trim(text.substr(start, end - start));
    start = end + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    const std::string where = label + ":" + std::to_string(line_no) + ": ";
    const std::vector<std::string_view> fields = splitFields(line);
    if (!have_header) {
      std::string got;
      for (std::size_t j = 0; j < fields.size(); ++j) {
        if (j > 0) got += ',';
        got += fields[j];
      }
      if (got != expected)
        throw InputError(where + "header must be '" + expected + "' for a cell with " +
                         std::to_string(m) + (m == 1 ? " finger" : " fingers") + ", got '" +
                         std::string(line) + "'");
      have_header = true;
      continue;
    }
    if (static_cast<int>(fields.size()) != columns)
      throw InputError(where + "expected " + std::to_string(columns) + " values (" + expected +
                       "), got " + std::to_string(fields.size()));
    ControlSegment seg;
    seg.line = line_no;
    seg.tau.resize(m + 1);
    for (int j = 0; j < columns; ++j) {
      const std::string what = where + "column '" + columnName(j) + "'";
      const double v = parseNumber(fields[j], what);
      if (j == 0) {
        if (!(v > 0.0))
          throw InputError(what + ": duration must be positive (got " + std::string(fields[j]) +
                           ")");
        seg.duration = v;
      } else {
        seg.tau[j - 1] = v;
      }
    }
    s.segments_.push_back(std::move(seg));
  }
  if (!have_header)
    throw InputError(label + ": empty controls file (expected the header '" + expected +
                     "' and at least one segment)");
  if (s.segments_.empty()) throw InputError(label + ": no segments after the header");
  return s;
}

double ControlSchedule::totalDuration() const {
  double t = 0.0;
  for (const ControlSegment& seg : segments_) t += seg.duration;
  return t;
}

}  // namespace rbsf::tools
