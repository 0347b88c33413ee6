#pragma once
// Private: Ipopt's TNLP over a TrajectoryProblem. Ipopt headers stay inside trajopt/src.

#include <atomic>
#include <chrono>

#include <IpTNLP.hpp>

#include "rbsf/trajopt/trajectory_problem.h"

namespace rbsf::trajopt {

/// \brief Stacks the problem's elements for Ipopt; keeps the final point and status.
class IpoptAdapter final : public Ipopt::TNLP {
 public:
  /// \brief `max_wall_time` [s]: Ipopt 3.11 has only a CPU-time limit, so the wall-time
  ///        limit is checked here at every iteration (wallTimeExceeded() then says so).
  IpoptAdapter(const TrajectoryProblem& problem, bool exact_hessian,
               const std::atomic<bool>* cancel, double max_wall_time)
      : problem_(problem),
        exact_hessian_(exact_hessian),
        cancel_(cancel),
        max_wall_time_(max_wall_time),
        start_(std::chrono::steady_clock::now()) {}

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override;
  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override;
  bool get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x, bool init_z,
                          Ipopt::Number* z_L, Ipopt::Number* z_U, Ipopt::Index m, bool init_lambda,
                          Ipopt::Number* lambda) override;
  bool eval_f(Ipopt::Index n, const Ipopt::Number* x, bool new_x,
              Ipopt::Number& obj_value) override;
  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool new_x,
                   Ipopt::Number* grad_f) override;
  bool eval_g(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Index m,
              Ipopt::Number* g) override;
  bool eval_jac_g(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Index m,
                  Ipopt::Index nele_jac, Ipopt::Index* iRow, Ipopt::Index* jCol,
                  Ipopt::Number* values) override;
  bool eval_h(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Number obj_factor,
              Ipopt::Index m, const Ipopt::Number* lambda, bool new_lambda, Ipopt::Index nele_hess,
              Ipopt::Index* iRow, Ipopt::Index* jCol, Ipopt::Number* values) override;
  bool intermediate_callback(Ipopt::AlgorithmMode mode, Ipopt::Index iter, Ipopt::Number obj_value,
                             Ipopt::Number inf_pr, Ipopt::Number inf_du, Ipopt::Number mu,
                             Ipopt::Number d_norm, Ipopt::Number regularization_size,
                             Ipopt::Number alpha_du, Ipopt::Number alpha_pr, Ipopt::Index ls_trials,
                             const Ipopt::IpoptData* ip_data,
                             Ipopt::IpoptCalculatedQuantities* ip_cq) override;
  void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index n, const Ipopt::Number* x,
                         const Ipopt::Number* z_L, const Ipopt::Number* z_U, Ipopt::Index m,
                         const Ipopt::Number* g, const Ipopt::Number* lambda,
                         Ipopt::Number obj_value, const Ipopt::IpoptData* ip_data,
                         Ipopt::IpoptCalculatedQuantities* ip_cq) override;

  /// \brief The last point Ipopt reported (finalize_solution).
  const Eigen::VectorXd& solution() const { return solution_; }
  /// \brief Worst violation of the constraints and bounds at the solution.
  double constraintViolation() const { return violation_; }
  int iterations() const { return iterations_; }
  bool wallTimeExceeded() const { return wall_time_exceeded_; }

 private:
  const TrajectoryProblem& problem_;
  bool exact_hessian_;
  const std::atomic<bool>* cancel_;
  Eigen::VectorXd solution_;
  double violation_ = 0.0;
  int iterations_ = 0;
  double max_wall_time_;
  std::chrono::steady_clock::time_point start_;
  bool wall_time_exceeded_ = false;
};

}  // namespace rbsf::trajopt
