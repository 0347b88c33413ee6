#include "rbsf/bench/run_list.h"

#include <charconv>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::bench {

std::uint32_t runSeed(const std::string& problem, const std::string& planner, int run) {
  const std::string key = problem + "/" + planner + "/" + std::to_string(run);
  std::uint32_t h = 2166136261u;  // FNV-1a, 32 bits
  for (unsigned char c : key) {
    h ^= c;
    h *= 16777619u;
  }
  return h == 0 ? 1 : h;
}

std::vector<RunSpec> makeRunList(const std::vector<std::string>& problems,
                                 const std::vector<std::string>& planners, int runs) {
  std::vector<RunSpec> list;
  for (std::size_t p = 0; p < problems.size(); ++p)
    for (const std::string& planner : planners)
      for (int r = 0; r < runs; ++r)
        list.push_back({list.size(), p, planner, r, runSeed(problems[p], planner, r)});
  return list;
}

std::vector<RunSpec> shardOf(const std::vector<RunSpec>& list, int k, int n) {
  std::vector<RunSpec> out;
  for (const RunSpec& r : list)
    if (static_cast<int>(r.index % static_cast<std::size_t>(n)) == k - 1) out.push_back(r);
  return out;
}

void parseShard(const std::string& text, const std::string& what, int& k, int& n) {
  const auto slash = text.find('/');
  auto number = [&](std::string_view s, int& v) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
  };
  if (slash == std::string::npos || !number(std::string_view(text).substr(0, slash), k) ||
      !number(std::string_view(text).substr(slash + 1), n) || n < 1 || k < 1 || k > n)
    throw InputError(what + ": expected k/N with 1 <= k <= N (got '" + text + "')");
}

}  // namespace rbsf::bench
