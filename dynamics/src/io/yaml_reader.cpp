#include "rbsf/dynamics/io/yaml_reader.h"

#include <charconv>
#include <set>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

std::string YamlReader::join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string YamlReader::describe(const YAML::Node& n) {
  if (n.IsNull()) return "an empty value";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "'" + n.Scalar() + "'";
}

YAML::Node YamlReader::load(const std::string& text) const {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail("malformed YAML at line " + std::to_string(e.mark.line + 1) + ", column " +
         std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

void YamlReader::mapping(const YAML::Node& n, const std::string& path,
                         std::initializer_list<std::string_view> allowed,
                         const std::string& what_root) const {
  const std::string what = path.empty() ? what_root : path;
  if (!n.IsMap()) fail(what + " must be a mapping (got " + describe(n) + ")");
  std::set<std::string> seen;
  for (const auto& kv : n) {
    if (!kv.first.IsScalar()) fail(what + " has a key that is not a plain name");
    const std::string key = kv.first.Scalar();
    if (!seen.insert(key).second) fail("duplicate key " + join(path, key));
    bool ok = false;
    std::string list;
    for (auto a : allowed) {
      ok = ok || key == a;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    if (!ok) fail("unknown key " + join(path, key) + " (expected one of: " + list + ")");
  }
}

YAML::Node YamlReader::get(const YAML::Node& map, const std::string& path, const char* key,
                           bool required) const {
  YAML::Node n = map[key];
  if (!n.IsDefined() && required) fail("missing key " + join(path, key));
  return n;
}

double YamlReader::number(const YAML::Node& n, const std::string& path) const {
  double v = 0;
  bool ok = false;
  if (n.IsScalar()) {
    try {
      v = n.as<double>();
      ok = true;
    } catch (const YAML::Exception&) {
    }
  }
  if (!ok) fail(path + " must be a number (got " + describe(n) + ")");
  if (!std::isfinite(v)) fail(path + " must be a finite number (got " + describe(n) + ")");
  return v;
}

double YamlReader::number(const YAML::Node& map, const std::string& path, const char* key,
                          double fallback, bool required) const {
  YAML::Node n = get(map, path, key, required);
  return n.IsDefined() ? number(n, join(path, key)) : fallback;
}

std::pair<double, double> YamlReader::pair(const YAML::Node& map, const std::string& path,
                                           const char* key, bool required,
                                           std::pair<double, double> fallback) const {
  const std::string p = join(path, key);
  YAML::Node n = get(map, path, key, required);
  if (!n.IsDefined()) return fallback;
  if (!n.IsSequence() || n.size() != 2)
    fail(p + " must be a list of 2 numbers (got " +
         (!n.IsSequence() ? describe(n)
          : n.size() == 1 ? std::string("1 entry")
                          : std::to_string(n.size()) + " entries") +
         ")");
  return {number(n[0], p + "[0]"), number(n[1], p + "[1]")};
}

std::string YamlReader::text(const YAML::Node& n, const std::string& path) const {
  if (!n.IsScalar()) fail(path + " must be a value (got " + describe(n) + ")");
  return n.Scalar();
}

}  // namespace rbsf
