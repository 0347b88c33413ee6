#pragma once
/// \file
/// \brief The summary table of benchmark logs: per problem (experiment) and planner.
///
/// | column | computed from the runs' properties |
/// |--------|------------------------------------|
/// | runs, solved | count; `solved` = OMPL's exact solution flag |
/// | success | solved / runs |
/// | time q1, median, q3 [s] | quartiles of `time` over all runs, an unsolved run counting as
/// infinitely slow (so "-" once more than that share is unsolved); linear interpolation between
/// order statistics | | prop/s | sum of `propagations` / sum of `time` over all runs | | duration
/// [s] | median `solution duration` (seconds of motion) over solved runs | | opt ok, cost red. |
/// with --optimize: optimiser successes / solved runs, median `cost reduction` over successes |
/// | cert. | with --optimize: runs whose kept plan is certified / solved runs |

#include <string>
#include <vector>

#include "rbsf/bench/benchmark_log.h"

namespace rbsf::bench {

/// \brief One line of the summary.
struct SummaryRow {
  std::string problem, planner;
  int runs = 0, solved = 0;
  double time_q1 = 0.0, time_median = 0.0, time_q3 = 0.0;  ///< [s], +inf: not reached
  double propagations_per_second = 0.0;
  double duration_median = -1.0;  ///< [s], < 0 when nothing solved
  double pivots_median = -1.0;    ///< the solved plans' pivots (Plan::pivots), < 0: none
  int optimized = 0, optimizer_success = 0;
  int certified = 0;  ///< --optimize: runs whose kept plan is certified
  double cost_reduction_median = 0.0;
};

/// \brief Quantile p in [0, 1] of sorted values (linear interpolation; +inf propagates).
double quantile(const std::vector<double>& sorted, double p);

/// \brief Rows for every planner of every log, in the logs' order.
std::vector<SummaryRow> summarize(const std::vector<ExperimentLog>& logs);

/// \brief The table as text (optimiser columns when `optimize`).
std::string formatSummary(const std::vector<SummaryRow>& rows, bool optimize);

}  // namespace rbsf::bench
