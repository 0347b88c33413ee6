#pragma once
/// \file
/// \brief Planner Arena databases: OMPL's ompl_benchmark_statistics (Debian package
///        ompl-demos, /usr/bin/ompl_benchmark_statistics) turns .log files into the SQLite
///        database Planner Arena (plannerarena.org) opens, with the tables experiments,
///        plannerConfigs, enums, runs and progress.

#include <string>
#include <vector>

namespace rbsf::bench {

/// \brief Path of ompl_benchmark_statistics: $RBSF_OMPL_BENCHMARK_STATISTICS if set, else
///        the first match on $PATH, /usr/bin, /usr/share/ompl/demos. Empty if none.
std::string findBenchmarkStatistics();

/// \brief Build `database` from `logs`: the script writes a temporary file in the same
///        folder, which is renamed into place (an existing database is replaced).
/// \throws std::runtime_error when the script is missing or fails.
void makeArenaDatabase(const std::vector<std::string>& logs, const std::string& database);

}  // namespace rbsf::bench
