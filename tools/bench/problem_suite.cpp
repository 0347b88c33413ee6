#include "rbsf/bench/problem_suite.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/input_file.h"
#include "rbsf/dynamics/io/yaml_reader.h"
#include "rbsf/tools/cli_values.h"

namespace rbsf::bench {

namespace {

/// A pose as "x,y,phi" or [x, y, phi].
Pose readPose(const YamlReader& rd, const YAML::Node& n, const std::string& path) {
  const std::string what = rd.prefix + path;
  if (n.IsScalar()) return tools::parsePose(n.Scalar(), what);
  if (!n.IsSequence() || n.size() != 3)
    rd.fail(path + " must be x,y,phi (a string or a list of 3 values; got " +
            YamlReader::describe(n) + ")");
  return {tools::parseNumber(rd.text(n[0], path + "[0]"), what + "[0]"),
          tools::parseNumber(rd.text(n[1], path + "[1]"), what + "[1]"),
          tools::parseAngle(rd.text(n[2], path + "[2]"), what + "[2]")};
}

bool goodName(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
      return false;
  return true;
}

BenchProblem readProblem(const YamlReader& rd, const YAML::Node& n, const std::string& path,
                         const std::filesystem::path& folder) {
  rd.mapping(n, path, {"name", "cell", "start", "start_theta", "goal", "goal_angle", "tolerances"});
  auto at = [&](const char* key) { return YamlReader::join(path, key); };
  BenchProblem p;
  p.name = rd.text(rd.get(n, path, "name"), at("name"));
  if (!goodName(p.name))
    rd.fail(at("name") + " '" + p.name +
            "' must be letters, digits, '-', '_' or '.' (it names the log file)");
  const std::string cell = rd.text(rd.get(n, path, "cell"), at("cell"));
  p.cell_path =
      (std::filesystem::path(cell).is_absolute() ? std::filesystem::path(cell) : folder / cell)
          .lexically_normal()
          .string();
  p.problem.start = readPose(rd, rd.get(n, path, "start"), at("start"));
  p.problem.goal = readPose(rd, rd.get(n, path, "goal"), at("goal"));
  if (const YAML::Node t = rd.get(n, path, "start_theta", false); t.IsDefined())
    p.problem.start_theta =
        tools::parseAngle(rd.text(t, at("start_theta")), rd.prefix + at("start_theta"));
  if (const YAML::Node g = rd.get(n, path, "goal_angle", false); g.IsDefined()) {
    const std::string mode = rd.text(g, at("goal_angle"));
    if (mode != "nearest" && mode != "absolute")
      rd.fail(at("goal_angle") + " must be nearest or absolute (got '" + mode + "')");
    p.problem.absolute_angle = mode == "absolute";
  }
  if (const YAML::Node t = rd.get(n, path, "tolerances", false); t.IsDefined()) {
    const std::string tp = at("tolerances");
    rd.mapping(t, tp, {"position", "angle"});
    const std::string pp = YamlReader::join(tp, "position"), ap = YamlReader::join(tp, "angle");
    if (const YAML::Node v = rd.get(t, tp, "position", false); v.IsDefined())
      p.problem.tolerance.position = tools::parseNumber(rd.text(v, pp), rd.prefix + pp);
    if (const YAML::Node v = rd.get(t, tp, "angle", false); v.IsDefined())
      p.problem.tolerance.angle = tools::parseAngle(rd.text(v, ap), rd.prefix + ap);
    rd.positive(p.problem.tolerance.position, pp);
    rd.positive(p.problem.tolerance.angle, ap);
  }
  return p;
}

}  // namespace

std::vector<BenchProblem> loadProblemSuite(const std::string& path) {
  return parseProblemSuite(readInputFile(path, "problem file"), path);
}

std::vector<BenchProblem> parseProblemSuite(const std::string& text, const std::string& path) {
  const YamlReader rd{{messagePrefix(path)}};
  const YAML::Node root = rd.load(text);
  rd.mapping(root, "", {"problems"}, "the problem file");
  const YAML::Node list = rd.get(root, "", "problems");
  if (!list.IsSequence() || list.size() == 0)
    rd.fail("problems must be a non-empty list of problems (got " + YamlReader::describe(list) +
            ")");
  const auto folder = std::filesystem::path(path).parent_path();
  std::vector<BenchProblem> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = "problems[" + std::to_string(i) + "]";
    try {
      out.push_back(readProblem(rd, list[i], where, folder));
    } catch (const YAML::Exception& e) {
      rd.fail(where + ": " + e.msg);
    }
    if (!names.insert(out.back().name).second)
      rd.fail(where + ".name: duplicate problem name '" + out.back().name + "'");
  }
  return out;
}

}  // namespace rbsf::bench
