#include "rbsf/trajopt/plan_optimizer.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include <IpIpoptApplication.hpp>

#include "ipopt_adapter.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/trajopt/trajectory_problem.h"

namespace rbsf::trajopt {

namespace {

plan::SolverStatus statusOf(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
      return plan::SolverStatus::kSolveSucceeded;
    case Ipopt::Solved_To_Acceptable_Level:
      return plan::SolverStatus::kSolvedToAcceptableLevel;
    case Ipopt::Infeasible_Problem_Detected:
      return plan::SolverStatus::kInfeasibleProblemDetected;
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return plan::SolverStatus::kSearchDirectionBecomesTooSmall;
    case Ipopt::Diverging_Iterates:
      return plan::SolverStatus::kDivergingIterates;
    case Ipopt::User_Requested_Stop:
      return plan::SolverStatus::kUserRequestedStop;
    case Ipopt::Feasible_Point_Found:
      return plan::SolverStatus::kFeasiblePointFound;
    case Ipopt::Maximum_Iterations_Exceeded:
      return plan::SolverStatus::kMaximumIterationsExceeded;
    case Ipopt::Restoration_Failed:
      return plan::SolverStatus::kRestorationFailed;
    case Ipopt::Error_In_Step_Computation:
      return plan::SolverStatus::kErrorInStepComputation;
    case Ipopt::Maximum_CpuTime_Exceeded:
      return plan::SolverStatus::kMaximumCpuTimeExceeded;
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return plan::SolverStatus::kNotEnoughDegreesOfFreedom;
    case Ipopt::Invalid_Problem_Definition:
      return plan::SolverStatus::kInvalidProblemDefinition;
    case Ipopt::Invalid_Option:
      return plan::SolverStatus::kInvalidOption;
    case Ipopt::Invalid_Number_Detected:
      return plan::SolverStatus::kInvalidNumberDetected;
    case Ipopt::Unrecoverable_Exception:
      return plan::SolverStatus::kUnrecoverableException;
    case Ipopt::NonIpopt_Exception_Thrown:
      return plan::SolverStatus::kNonIpoptExceptionThrown;
    case Ipopt::Insufficient_Memory:
      return plan::SolverStatus::kInsufficientMemory;
    case Ipopt::Internal_Error:
      return plan::SolverStatus::kInternalError;
  }
  return plan::SolverStatus::kUnknownStatus;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("optimizer setting " + what);
}

void checkPlan(const RbsfModel& model, const plan::Plan& plan) {
  const int n = model.configDim(), nu = model.controlDim(), m = model.numFingers();
  auto bad = [](const std::string& what) {
    throw InputError("plan does not fit the cell: " + what);
  };
  if (plan.q0.size() != n)
    bad("q0 has " + std::to_string(plan.q0.size()) + " entries, expected " + std::to_string(n));
  if (!(plan.simulator.time_step > 0.0)) bad("time_step must be positive");
  for (std::size_t s = 0; s < plan.segments.size(); ++s)
    if (plan.segments[s].tau.size() != nu || !(plan.segments[s].duration > 0.0))
      bad("segments[" + std::to_string(s) + "] has a tau of the wrong size or no duration");
  if (plan.samples.empty()) bad("it has no samples");
  for (std::size_t s = 0; s < plan.samples.size(); ++s) {
    const plan::PlanSample& p = plan.samples[s];
    if (p.q.size() != n || p.v.size() != n || p.f_n.size() != m)
      bad("samples[" + std::to_string(s) + "] has vectors of the wrong size");
  }
}

/// Ipopt's options for `s`: quiet banner, MUMPS with PORD ordering, the problem's own scaling,
/// the Hessian, output, budget and tolerance asked for, and the derivative test when asked.
void setIpoptOptions(Ipopt::OptionsList& o, const OptimizerSettings& s) {
  o.SetStringValue("sb", "yes");
  o.SetStringValue("linear_solver", "mumps");
  // PORD ordering: about a third less factorization time than MUMPS's automatic choice on
  // the benchmark's 100-knot problems (block-banded KKT with one dense row per run).
  o.SetIntegerValue("mumps_pivot_order", 4);
  o.SetStringValue("nlp_scaling_method", "user-scaling");  // DecisionVariables::scaling()
  // At most 3 iterative-refinement steps per linear solve (Ipopt's default is 10): on the
  // benchmark's plans the same or fewer iterations at about 15 % less time each; the extra
  // back-solves, where refinement stalls short of residual_ratio_max on a poorly
  // conditioned KKT system, bought nothing.
  o.SetIntegerValue("max_refinement_steps", 3);
  o.SetStringValue("hessian_approximation", s.exact_hessian ? "exact" : "limited-memory");
  o.SetIntegerValue("print_level", s.print_level);
  o.SetIntegerValue("max_iter", s.max_iterations);
  o.SetNumericValue("tol", s.tolerance);
  o.SetNumericValue("max_cpu_time", s.max_solve_time);
  if (s.derivative_test) {
    o.SetStringValue("derivative_test", "first-order");
    o.SetNumericValue("derivative_test_tol", 1e-5);
    o.SetNumericValue("derivative_test_perturbation", 1e-8);  // Ipopt's default, stated
    if (!s.derivative_test_file.empty()) {
      o.SetStringValue("output_file", s.derivative_test_file);
      o.SetIntegerValue("file_print_level", 5);
    }
  }
}

/// Why the solve is not used: Ipopt's status, its iterations and (when the solution has the
/// problem's size) the constraint violation; the planner's plan is kept.
std::string notConvergedMessage(const plan::OptimizationSummary& summary, const IpoptAdapter& nlp,
                                const TrajectoryProblem& problem) {
  const Eigen::VectorXd& z = nlp.solution();
  std::ostringstream msg;
  msg << "Ipopt did not converge (" << plan::toString(summary.status) << " after "
      << summary.iterations << " iterations";
  if (z.size() == problem.size()) msg << ", constraint violation " << nlp.constraintViolation();
  msg << "); the planner's plan is kept";
  return msg.str();
}

}  // namespace

PlanOptimizer::PlanOptimizer(const RbsfModel& model, OptimizerSettings settings)
    : model_(model), settings_(std::move(settings)) {
  const OptimizerSettings& s = settings_;
  require(s.knots >= 2, "knots = " + std::to_string(s.knots) + " must be >= 2");
  require(std::isfinite(s.smoothness_weight) && s.smoothness_weight >= 0.0,
          "smoothness_weight must be finite and >= 0");
  require(std::isfinite(s.force_weight) && s.force_weight >= 0.0,
          "force_weight must be finite and >= 0");
  require(s.duration_min_scale > 0.0 && s.duration_min_scale <= 1.0,
          "duration_min_scale must be in (0, 1]");
  require(std::isfinite(s.duration_max_scale) && s.duration_max_scale >= 1.0,
          "duration_max_scale must be finite and >= 1");
  require(s.cone_margin > 0.0 && s.cone_margin <= 1.0, "cone_margin must be in (0, 1]");
  require(std::isfinite(s.tube_position) && s.tube_position >= 0.0 && std::isfinite(s.tube_angle) &&
              s.tube_angle >= 0.0,
          "tube_position and tube_angle must be finite and >= 0");
  require(std::isfinite(s.normal_floor) && s.normal_floor >= 0.0,
          "normal_floor must be finite and >= 0");
  require(std::isfinite(s.min_slip_rate) && s.min_slip_rate >= 0.0, "min_slip_rate must be >= 0");
  require(s.max_iterations >= 0, "max_iterations must be >= 0");
  require(s.tolerance > 0.0, "tolerance must be positive");
  require(s.max_solve_time > 0.0, "max_solve_time must be positive");
  require(s.print_level >= 0 && s.print_level <= 12, "print_level must be in [0, 12]");
}

OptimizedPlan PlanOptimizer::optimize(const plan::Plan& plan,
                                      const std::atomic<bool>* cancel) const {
  checkPlan(model_, plan);
  OptimizedPlan out;
  out.plan = plan;
  plan::OptimizationSummary& summary = out.summary;
  summary.ran = true;
  summary.cost_before = planEffort(model_, plan);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  const TrajectoryProblem problem(model_, plan, settings_);
  if (!problem.ok()) {
    summary.status = plan::SolverStatus::kNotSolved;
    summary.message = "optimisation not attempted: " + problem.why();
    summary.cost_after = summary.cost_before;
    summary.solve_time = elapsed();
    return out;
  }

  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  setIpoptOptions(*app->Options(), settings_);
  // "": no options file. Ipopt would otherwise read ./ipopt.opt, and a stray file in the
  // caller's working directory would silently change every plan optimised from there.
  Ipopt::ApplicationReturnStatus status = app->Initialize("");
  Ipopt::SmartPtr<IpoptAdapter> nlp =
      new IpoptAdapter(problem, settings_.exact_hessian, cancel, settings_.max_solve_time);
  if (status == Ipopt::Solve_Succeeded) status = app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));
  summary.solve_time = elapsed();
  summary.status =
      nlp->wallTimeExceeded() ? plan::SolverStatus::kMaximumWallTimeExceeded : statusOf(status);
  summary.iterations = nlp->iterations();
  const bool converged =
      status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level;
  const Eigen::VectorXd& z = nlp->solution();
  if (!converged || z.size() != problem.size() || !z.allFinite()) {
    summary.message = notConvergedMessage(summary, *nlp, problem);
    summary.cost_after = summary.cost_before;
    return out;
  }
  summary.cost_after = problem.effort(z);
  out.plan = problem.toPlan(z, plan);
  const DecisionLayout& dl = problem.layout();
  for (int k = 0; k < dl.knots(); ++k) {
    out.f_t.push_back(z.segment(dl.ft(k), dl.fingers()));
    out.xi.push_back(z.segment(dl.xi(k), dl.fingers()));
  }
  out.success = true;
  return out;
}

}  // namespace rbsf::trajopt
