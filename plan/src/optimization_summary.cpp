#include "rbsf/plan/optimization_summary.h"

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::plan {

const std::array<SolverStatus, 22>& solverStatuses() {
  static const std::array<SolverStatus, 22> all = {SolverStatus::kSolveSucceeded,
                                                   SolverStatus::kSolvedToAcceptableLevel,
                                                   SolverStatus::kInfeasibleProblemDetected,
                                                   SolverStatus::kSearchDirectionBecomesTooSmall,
                                                   SolverStatus::kDivergingIterates,
                                                   SolverStatus::kUserRequestedStop,
                                                   SolverStatus::kFeasiblePointFound,
                                                   SolverStatus::kMaximumIterationsExceeded,
                                                   SolverStatus::kRestorationFailed,
                                                   SolverStatus::kErrorInStepComputation,
                                                   SolverStatus::kMaximumCpuTimeExceeded,
                                                   SolverStatus::kMaximumWallTimeExceeded,
                                                   SolverStatus::kNotEnoughDegreesOfFreedom,
                                                   SolverStatus::kInvalidProblemDefinition,
                                                   SolverStatus::kInvalidOption,
                                                   SolverStatus::kInvalidNumberDetected,
                                                   SolverStatus::kUnrecoverableException,
                                                   SolverStatus::kNonIpoptExceptionThrown,
                                                   SolverStatus::kInsufficientMemory,
                                                   SolverStatus::kInternalError,
                                                   SolverStatus::kNotSolved,
                                                   SolverStatus::kUnknownStatus};
  return all;
}

const char* toString(SolverStatus status) {
  switch (status) {
    case SolverStatus::kSolveSucceeded:
      return "Solve_Succeeded";
    case SolverStatus::kSolvedToAcceptableLevel:
      return "Solved_To_Acceptable_Level";
    case SolverStatus::kInfeasibleProblemDetected:
      return "Infeasible_Problem_Detected";
    case SolverStatus::kSearchDirectionBecomesTooSmall:
      return "Search_Direction_Becomes_Too_Small";
    case SolverStatus::kDivergingIterates:
      return "Diverging_Iterates";
    case SolverStatus::kUserRequestedStop:
      return "User_Requested_Stop";
    case SolverStatus::kFeasiblePointFound:
      return "Feasible_Point_Found";
    case SolverStatus::kMaximumIterationsExceeded:
      return "Maximum_Iterations_Exceeded";
    case SolverStatus::kRestorationFailed:
      return "Restoration_Failed";
    case SolverStatus::kErrorInStepComputation:
      return "Error_In_Step_Computation";
    case SolverStatus::kMaximumCpuTimeExceeded:
      return "Maximum_CpuTime_Exceeded";
    case SolverStatus::kMaximumWallTimeExceeded:
      return "Maximum_WallTime_Exceeded";
    case SolverStatus::kNotEnoughDegreesOfFreedom:
      return "Not_Enough_Degrees_Of_Freedom";
    case SolverStatus::kInvalidProblemDefinition:
      return "Invalid_Problem_Definition";
    case SolverStatus::kInvalidOption:
      return "Invalid_Option";
    case SolverStatus::kInvalidNumberDetected:
      return "Invalid_Number_Detected";
    case SolverStatus::kUnrecoverableException:
      return "Unrecoverable_Exception";
    case SolverStatus::kNonIpoptExceptionThrown:
      return "NonIpopt_Exception_Thrown";
    case SolverStatus::kInsufficientMemory:
      return "Insufficient_Memory";
    case SolverStatus::kInternalError:
      return "Internal_Error";
    case SolverStatus::kNotSolved:
      return "Not_Solved";
    case SolverStatus::kUnknownStatus:
      return "Unknown_Status";
  }
  return "Unknown_Status";
}

SolverStatus parseSolverStatus(std::string_view name, const std::string& where) {
  for (SolverStatus s : solverStatuses())
    if (name == toString(s)) return s;
  throw InputError(where + ": unknown optimiser status '" + std::string(name) + "'");
}

bool converged(SolverStatus status) {
  return status == SolverStatus::kSolveSucceeded ||
         status == SolverStatus::kSolvedToAcceptableLevel;
}

}  // namespace rbsf::plan
