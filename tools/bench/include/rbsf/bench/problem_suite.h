#pragma once
/// \file
/// \brief Benchmark problem files: a list of reorientation problems on cells.
///
/// Format (YAML):
///
///     problems:
///       - name: 180deg                  # letters, digits, '-', '_', '.'; unique
///         cell: ../default.yaml         # relative to the problem file
///         start: 0.1,0.40,0             # x,y,phi of the COM at rest [m, m, rad|deg]
///         start_theta: 0                # optional base angle at the start (default 0)
///         goal: -0.1,0.40,180deg        # x,y,phi of the goal
///         goal_angle: nearest           # optional: nearest (default) | absolute
///         tolerances: {position: 0.01, angle: 2deg}   # [m], angle [rad|deg]
///
/// Poses are "x,y,phi" strings or sequences [x, y, phi]; angles take the deg suffix of
/// cli_values.h. goal_angle: nearest compares phi modulo 2 pi (270 deg is -90 deg);
/// absolute compares the part's accumulated angle, so a start at 0 and a goal at -270deg
/// asks for a 270 degree clockwise turn (planner::Problem::absolute_angle).
/// Errors are InputErrors naming the file, the problem and the key:
/// "suite.yaml: problems[1] (90deg): goal: expected 3 numbers (x,y,phi), got 2".

#include <string>
#include <vector>

#include "rbsf/planner/kinodynamic/reorientation_planner.h"

namespace rbsf::bench {

/// \brief One benchmark problem.
struct BenchProblem {
  std::string name;
  std::string cell_path;     ///< resolved against the problem file's folder
  planner::Problem problem;  ///< with the problem's `tolerances` (Problem::tolerance)
};

/// \brief Read a problem file. \throws InputError (file, problem, key) for bad content,
///        an unreadable file, duplicate names or an empty list.
std::vector<BenchProblem> loadProblemSuite(const std::string& path);

/// \brief The problems of a problem file's text; `path` names it in messages and its folder
///        resolves the cells (each cell file is read and checked).
std::vector<BenchProblem> parseProblemSuite(const std::string& text, const std::string& path);

}  // namespace rbsf::bench
