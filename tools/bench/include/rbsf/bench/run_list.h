#pragma once
/// \file
/// \brief The list of benchmark runs, their seeds and its deterministic split into shards.
///
/// The run list is every (problem, planner, run index) in the order problems (file
/// order) x planners (given order) x run index 0..runs-1; entry i of that list has index
/// i. Shard k of N (1 <= k <= N) holds the entries with i mod N = k - 1: every run is in
/// exactly one shard, the shards' sizes differ by at most one, and each shard mixes the
/// problems and planners, so the N jobs take about the same time.
///
/// A run's seed depends only on (problem name, planner, run index): the 32-bit FNV-1a
/// hash of "problem/planner/run", 0 mapped to 1 (OMPL's RNG::setSeed refuses 0). So a run
/// gets the same seed in a full run, in any shard and with any --jobs.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rbsf::bench {

/// \brief One benchmark run.
struct RunSpec {
  std::size_t index = 0;    ///< position in the unsharded run list
  std::size_t problem = 0;  ///< index into the problem list
  std::string planner;
  int run = 0;  ///< run index for this problem and planner, 0-based
  std::uint32_t seed = 1;
};

/// \brief The seed of a run (see the file comment).
std::uint32_t runSeed(const std::string& problem, const std::string& planner, int run);

/// \brief The whole run list for problems named `problems`.
std::vector<RunSpec> makeRunList(const std::vector<std::string>& problems,
                                 const std::vector<std::string>& planners, int runs);

/// \brief Shard k of n (1-based k) of a run list.
std::vector<RunSpec> shardOf(const std::vector<RunSpec>& list, int k, int n);

/// \brief Parse "k/N" (1 <= k <= N). \throws InputError naming `what`.
void parseShard(const std::string& text, const std::string& what, int& k, int& n);

}  // namespace rbsf::bench
