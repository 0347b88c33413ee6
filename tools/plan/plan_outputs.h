#pragma once
/// \file
/// \brief The files plan-reorientation writes: the plan as JSON (--out) and CSV (--csv),
///        the animated SVG (--svg) and the HTML report (--report).
///
/// Paths are checked before the search (a missing or read-only directory is bad input
/// and costs no planning time). At the end every text is formatted first and then each
/// file is written to a temporary name and renamed (rbsf/dynamics/io/atomic_file.h): a file
/// is complete or absent, and a plan holding a NaN writes none. With `reproducible`,
/// wall-clock fields (planning_time) are left out, so the same seed gives byte-identical
/// files.

#include <string>
#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/tools/html_report.h"
#include "rbsf/tools/trajectory_writer.h"

namespace rbsf::tools {

/// \brief How far configuration `q` leaves the part from `goal`: "0.123 m and 35.2 deg from
///        the goal" (the angle compared as the problem reads it, planner/goal.h).
std::string goalDistanceText(const VecQ& q, const Pose& goal, bool absolute_angle);

/// \brief Output options of plan-reorientation.
struct PlanOutputOptions {
  std::string json, csv, svg, report;  ///< paths; empty: not written
  bool reproducible = false;           ///< leave wall-clock fields out
  double svg_still = 0.0;              ///< [s] frame shown by viewers that do not animate
  std::string cell_label;              ///< the cell as named on the command line
};

/// \brief Checks and writes the outputs of one run.
class PlanOutputs {
 public:
  /// \throws InputError for an unwritable path or two outputs with the same path.
  explicit PlanOutputs(PlanOutputOptions options);

  /// \brief True when any file is requested.
  bool any() const;

  /// \brief Format every requested file, then write each atomically.
  /// \throws std::runtime_error for a NaN in the plan, InputError for an I/O failure.
  ///        `sections` go into the report below its summary.
  void write(const RbsfModel& model, const plan::PlanRecord& record,
             const std::vector<ReportSection>& sections = {}) const;

  /// \brief The plan's samples as drawn (the start q0 alone when the plan has none).
  static std::vector<TrajectorySample> frames(const RbsfModel& model, const plan::Plan& plan);

 private:
  PlanOutputOptions o_;
};

}  // namespace rbsf::tools
