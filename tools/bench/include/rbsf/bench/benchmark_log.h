#pragma once
/// \file
/// \brief OMPL benchmark log files (the text ompl::tools::Benchmark::saveResultsToFile
///        writes and ompl_benchmark_statistics reads): parse, merge, write.
///
/// Layout of a log (OMPL 1.5):
///
///     [OMPL version line], Experiment <name>, Running on <host>, Starting at <date>,
///     <<<| setup text |>>>, [<<<| cpu info |>>>], <seed> is the random seed,
///     <t> seconds per run, <mb> MB per run, <n> runs per planner,
///     <s> seconds spent to collect the data          (the header, kept as lines)
///     1 enum type / status|Unknown status|...        (enum lines)
///     <P> planners, then per planner:
///       <name> / <k> common properties + "key = value" lines /
///       <q> properties for each run + "name TYPE" lines / <r> runs + "v; v; ...; " lines /
///       [<p> progress properties for each run + names / <r> runs + lines] / "."
///
/// rbsf-bench runs each run in its own process with a one-run benchmark; the runs of one
/// problem are then merged into one experiment (one log per problem, one experiment in
/// Planner Arena), and `rbsf-bench merge` merges shards the same way. Merging keeps the
/// first log's header (with the run count and the total time updated and seed 0: each
/// run's own seed is its "seed" property) and joins every planner's runs, ordered by the
/// "run index" property; enums and property columns are the union, a missing value left empty
/// (NULL in the database), as OMPL does.

#include <map>
#include <string>
#include <vector>

namespace rbsf::bench {

/// \brief One run: property name with type ("time REAL") -> value text ("" when the run
///        has no value: NULL in the database).
struct LogRun {
  std::map<std::string, std::string> values;
  std::string progress;  ///< the run's progress line (empty when none)
};

/// \brief One planner's block.
struct PlannerLog {
  std::string name;                 ///< e.g. "control_KPIECE1"
  std::vector<std::string> common;  ///< "key = value" lines
  std::vector<LogRun> runs;
  std::vector<std::string> progress_names;  ///< empty when no progress data
};

/// \brief One experiment (one log file).
struct ExperimentLog {
  std::vector<std::string> header;  ///< lines before the enum count
  std::vector<std::string> enums;   ///< enum lines ("status|...")
  std::vector<PlannerLog> planners;

  /// \brief The name after "Experiment ".
  std::string name() const;
  /// \brief Runs of all planners.
  std::size_t runCount() const;
};

/// \brief Parse a log's text. \throws InputError naming `label` and the line.
ExperimentLog parseLog(const std::string& text, const std::string& label);

/// \brief Read a log file. \throws InputError.
ExperimentLog readLog(const std::string& path);

/// \brief The log's text, in OMPL's format (properties sorted by name).
std::string formatLog(const ExperimentLog& log);

/// \brief Add `from`'s runs to `into` (same experiment name required; planners matched by
///        name, new planners appended), keep runs ordered by "run index INTEGER", and
///        update the header (runs per planner, total time, seed 0).
/// \throws InputError when the experiment names differ or a run index appears twice.
void mergeLog(ExperimentLog& into, const ExperimentLog& from);

}  // namespace rbsf::bench
