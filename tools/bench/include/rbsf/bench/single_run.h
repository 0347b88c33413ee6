#pragma once
/// \file
/// \brief One benchmark run: ompl::tools::Benchmark with one planner and one run on the
///        planner's own setup (ReorientationPlanner::setup), in a process of its own.
///
/// OMPL 1.5's seed (ompl::RNG::setSeed) is global to the process and only takes effect
/// before the first random number generator exists, so rbsf-bench runs every run in a
/// fresh child process that seeds OMPL first: a run's result depends only on its seed and
/// settings, never on which runs came before or ran beside it (--jobs, --shard).
///
/// rbsf's own figures are added to OMPL's run properties by the post-run event (the names
/// are the columns of Planner Arena's runs table, spaces becoming underscores):
///   - `run index INTEGER`, `seed INTEGER`: the run (run_list.h);
///   - `propagations INTEGER`: SimPropagator::propagate calls of the search (excluding
///     OMPL's check of the solution path afterwards); `simulator steps INTEGER`: the
///     simulator steps of those propagations; `propagations per second REAL`: propagations
///     over OMPL's `time`;
///   - `best goal distance REAL`: least goal distance reached (tolerance units, <= 1: goal);
///   - the support planner (kSupportPlanner, support_ompl_planner.h): `expansions INTEGER`
///     of its searches, and 0 propagations (it only propagates to replay its plan into the
///     path); its exact solutions' plan is its own;
///   - exact solutions: `solution duration REAL` (seconds of motion of the plan), `path
///     mismatch REAL` (re-simulated plan against the planner's states);
///   - with --optimize, exact solutions, the product's refinement (planner::refineAndCertify:
///     optimise, certify the planner's plan and the refinement, keep the better):
///     `optimizer success BOOLEAN`, `optimizer status ENUM` (Ipopt's status, enum
///     "optimizer status" in the log), `optimizer iterations INTEGER`, `optimizer time REAL`,
///     `cost before REAL`, `cost after REAL`, `cost reduction REAL` (1 - after / before) of
///     the summarised solve; `refined chosen BOOLEAN` (the refinement is the plan kept),
///     `certified BOOLEAN`, `certificate success rate REAL`, `certificate lower bound REAL`
///     (its Clopper-Pearson lower bound, plan/confidence.h) and `certificate trials INTEGER`
///     (the default sequential certificate's count) of the plan kept.

#include <string>

#include "rbsf/bench/problem_suite.h"
#include "rbsf/bench/run_list.h"

namespace rbsf::bench {

/// \brief The support planner's name in --planners (the others: planner::parsePlanner's names).
inline const std::string kSupportPlanner = "Support";

/// \brief Settings shared by every run.
struct RunSettings {
  double time_limit = 30.0;  ///< [s]
  bool optimize = false;
};

/// \brief Run `spec` on `problem` (model of its cell) and write the one-run OMPL log to
///        `log_path` (atomically). Seeds OMPL: call once per process, before anything
///        else has created an OMPL random number generator.
void runSingle(const BenchProblem& problem, const RbsfModel& model, const RunSpec& spec,
               const RunSettings& settings, const std::string& log_path);

}  // namespace rbsf::bench
