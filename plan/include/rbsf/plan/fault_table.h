#pragma once
/// \file
/// \brief How a plan's trials end under faults (faults.h, trial.h): one row per kind of
///        fault (its trials alone) and one for all of them together, for rbsf-replay.

#include <string>
#include <utility>
#include <vector>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/plan/certificate_report.h"

namespace rbsf::plan {

/// \brief The trials of one kind of fault, and how they ended (TrialEnd).
struct FaultRow {
  std::string kind;  ///< "pose dropouts", ..., "all faults"
  int trials = 0;
  int done = 0, held = 0, lost = 0, off = 0;
  int lost_unreported = 0;   ///< lost without leaving or holding reported within 50 ms
  int with_fault = 0;        ///< trials in which a fault acted
  int seen = 0;              ///< ... and the status flagged it
  double median_seen = 0.0;  ///< median time from the fault to the flag [s]
  double max_seen = 0.0;     ///< largest [s]
  std::vector<std::pair<HoldReason, int>> hold_reasons;  ///< held trials by reason
};

/// \brief The row of `outcomes` (trials of one kind of fault).
FaultRow faultRow(const std::string& kind, const std::vector<TrialOutcome>& outcomes);

/// \brief Each kind of fault `cell` declares, with a copy of the cell that draws that kind
///        alone: "pose dropouts", "joint spikes", "missed ticks", "force cut", "mass error".
std::vector<std::pair<std::string, Cell>> faultKinds(const Cell& cell);

/// \brief The table as text: a header and one line per row (counts, the share done or held,
///        the fault-to-flag times in milliseconds).
std::string faultTableText(const std::vector<FaultRow>& rows);

}  // namespace rbsf::plan
