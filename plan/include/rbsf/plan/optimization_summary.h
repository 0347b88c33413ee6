#pragma once
/// \file
/// \brief How the trajectory optimiser's solve of a plan went (plan file key
///        `optimization`, plan_file.h): Ipopt's return status as a value, and the summary
///        a refined plan's record carries.

#include <array>
#include <string>
#include <string_view>

namespace rbsf::plan {

/// \brief Ipopt's return statuses (its ApplicationReturnStatus, in the order of its
///        IpReturnCodes), the optimiser's wall-time stop (kMaximumWallTimeExceeded),
///        kNotSolved (no NLP was built: the plan did not fit the optimiser's schedule) and
///        kUnknownStatus (a code this list does not know). Plan files and benchmark logs
///        write the names toString() gives, Ipopt's own.
enum class SolverStatus {
  kSolveSucceeded,
  kSolvedToAcceptableLevel,
  kInfeasibleProblemDetected,
  kSearchDirectionBecomesTooSmall,
  kDivergingIterates,
  kUserRequestedStop,
  kFeasiblePointFound,
  kMaximumIterationsExceeded,
  kRestorationFailed,
  kErrorInStepComputation,
  kMaximumCpuTimeExceeded,
  kMaximumWallTimeExceeded,
  kNotEnoughDegreesOfFreedom,
  kInvalidProblemDefinition,
  kInvalidOption,
  kInvalidNumberDetected,
  kUnrecoverableException,
  kNonIpoptExceptionThrown,
  kInsufficientMemory,
  kInternalError,
  kNotSolved,
  kUnknownStatus,
};

/// \brief Every SolverStatus in declaration order (the benchmark log's enum values).
const std::array<SolverStatus, 22>& solverStatuses();
/// \brief Ipopt's name of the status, e.g. "Solve_Succeeded".
const char* toString(SolverStatus status);
/// \brief The status named `name` (toString's words). \throws InputError naming `where`
///        and the name when no status has it.
SolverStatus parseSolverStatus(std::string_view name, const std::string& where);
/// \brief Ipopt converged: kSolveSucceeded or kSolvedToAcceptableLevel.
bool converged(SolverStatus status);

/// \brief How the optimiser's solve went (plan file key `optimization`).
struct OptimizationSummary {
  bool ran = false;  ///< false: not optimised (--no-optimize), key not written
  SolverStatus status = SolverStatus::kNotSolved;
  int iterations = 0;
  double solve_time = 0.0;   ///< [s]
  double cost_before = 0.0;  ///< effort integral of tau^T W tau on the planner's plan
  double cost_after = 0.0;   ///< and on the optimised one (trajopt's EffortCost)
  bool chosen = false;       ///< the plan in the file is the optimised one
  /// \brief Success rate of the optimised plan's certificate; -1 when it was not certified.
  double refined_success_rate = -1.0;
  std::string message;  ///< why it failed or was not chosen, empty otherwise
};

}  // namespace rbsf::plan
