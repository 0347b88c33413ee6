#include "rbsf/bench/problem_suite.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>

#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/input_file.h"
#include "rbsf/tools/cli_values.h"

namespace rbsf::bench {

namespace {

/// A pose as "x,y,phi" or [x, y, phi]; `what` prefixes every message.
Pose readPose(const YAML::Node& n, const std::string& what) {
  if (n.IsScalar()) return tools::parsePose(n.Scalar(), what);
  if (!n.IsSequence() || n.size() != 3)
    throw InputError(what + ": expected x,y,phi (a string or a list of 3 values)");
  return {tools::parseNumber(n[0].Scalar(), what + "[0]"),
          tools::parseNumber(n[1].Scalar(), what + "[1]"),
          tools::parseAngle(n[2].Scalar(), what + "[2]")};
}

std::string scalar(const YAML::Node& n, const std::string& what) {
  if (!n.IsScalar()) throw InputError(what + ": expected a value");
  return n.Scalar();
}

bool goodName(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
      return false;
  return true;
}

BenchProblem readProblem(const YAML::Node& n, const std::string& where,
                         const std::filesystem::path& folder) {
  if (!n.IsMap()) throw InputError(where + ": expected a mapping");
  if (!n["name"]) throw InputError(where + ": missing key 'name'");
  BenchProblem p;
  p.name = scalar(n["name"], where + ": name");
  if (!goodName(p.name))
    throw InputError(where + ": name '" + p.name +
                     "' must be letters, digits, '-', '_' or '.' (it names the log file)");
  const std::string at = where + " (" + p.name + ")";
  static const std::set<std::string> keys = {"name", "cell",       "start",     "start_theta",
                                             "goal", "goal_angle", "tolerances"};
  std::set<std::string> seen;
  for (const auto& kv : n) {
    const std::string k = kv.first.Scalar();
    if (!keys.count(k)) throw InputError(at + ": unknown key '" + k + "'");
    if (!seen.insert(k).second) throw InputError(at + ": duplicate key '" + k + "'");
  }
  for (const char* k : {"cell", "start", "goal"})
    if (!n[k]) throw InputError(at + ": missing key '" + k + "'");
  const std::string cell = scalar(n["cell"], at + ": cell");
  p.cell_path =
      (std::filesystem::path(cell).is_absolute() ? std::filesystem::path(cell) : folder / cell)
          .lexically_normal()
          .string();
  p.problem.start = readPose(n["start"], at + ": start");
  p.problem.goal = readPose(n["goal"], at + ": goal");
  if (n["start_theta"])
    p.problem.start_theta =
        tools::parseAngle(scalar(n["start_theta"], at + ": start_theta"), at + ": start_theta");
  if (n["goal_angle"]) {
    const std::string mode = scalar(n["goal_angle"], at + ": goal_angle");
    if (mode != "nearest" && mode != "absolute")
      throw InputError(at + ": goal_angle must be nearest or absolute (got '" + mode + "')");
    p.problem.absolute_angle = mode == "absolute";
  }
  if (const YAML::Node t = n["tolerances"]) {
    if (!t.IsMap()) throw InputError(at + ": tolerances: expected {position: .., angle: ..}");
    for (const auto& kv : t) {
      const std::string k = kv.first.Scalar();
      const std::string what = at + ": tolerances." + k;
      if (k == "position")
        p.position_tolerance = tools::parseNumber(scalar(kv.second, what), what);
      else if (k == "angle")
        p.angle_tolerance = tools::parseAngle(scalar(kv.second, what), what);
      else
        throw InputError(at + ": tolerances: unknown key '" + k + "'");
      if (!(k == "position" ? p.position_tolerance > 0 : p.angle_tolerance > 0))
        throw InputError(what + " must be positive");
    }
  }
  return p;
}

}  // namespace

std::vector<BenchProblem> loadProblemSuite(const std::string& path) {
  return parseProblemSuite(readInputFile(path, "problem file"), path);
}

std::vector<BenchProblem> parseProblemSuite(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(path + ": not valid YAML: " + e.msg);
  }
  if (!root.IsMap() || !root["problems"] || root.size() != 1)
    throw InputError(path + ": expected one key 'problems' holding a list of problems");
  const YAML::Node list = root["problems"];
  if (!list.IsSequence() || list.size() == 0)
    throw InputError(path + ": problems: expected a non-empty list");
  const auto folder = std::filesystem::path(path).parent_path();
  std::vector<BenchProblem> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = path + ": problems[" + std::to_string(i) + "]";
    try {
      out.push_back(readProblem(list[i], where, folder));
    } catch (const YAML::Exception& e) {
      throw InputError(where + ": " + e.msg);
    }
    if (!names.insert(out.back().name).second)
      throw InputError(where + ": duplicate problem name '" + out.back().name + "'");
  }
  return out;
}

}  // namespace rbsf::bench
