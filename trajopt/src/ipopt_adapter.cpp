#include "ipopt_adapter.h"

#include <algorithm>

namespace rbsf::trajopt {

using Ipopt::Index;
using Ipopt::Number;
using Map = Eigen::Map<const Eigen::VectorXd>;

bool IpoptAdapter::get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                                IndexStyleEnum& index_style) {
  n = problem_.size();
  m = problem_.rows();
  nnz_jac_g = problem_.nonZeros();
  nnz_h_lag = exact_hessian_ ? problem_.hessianPattern().size() : 0;
  index_style = C_STYLE;
  return true;
}

bool IpoptAdapter::get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                                   Number* g_u) {
  Eigen::VectorXd lo, up;
  problem_.variables().bounds(lo, up);
  std::copy_n(lo.data(), n, x_l);
  std::copy_n(up.data(), n, x_u);
  problem_.constraintBounds(lo, up);
  std::copy_n(lo.data(), m, g_l);
  std::copy_n(up.data(), m, g_u);
  return true;
}

bool IpoptAdapter::get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*,
                                      Number*, Index, bool init_lambda, Number*) {
  if (init_z || init_lambda) return false;
  if (init_x) {
    const Eigen::VectorXd z0 = problem_.variables().initialGuess();
    std::copy_n(z0.data(), n, x);
  }
  return true;
}

bool IpoptAdapter::eval_f(Index n, const Number* x, bool, Number& obj_value) {
  obj_value = problem_.objective(Map(x, n));
  return std::isfinite(obj_value);
}

bool IpoptAdapter::eval_grad_f(Index n, const Number* x, bool, Number* grad_f) {
  Eigen::Map<Eigen::VectorXd> g(grad_f, n);
  problem_.gradient(Map(x, n), g);
  return true;
}

bool IpoptAdapter::eval_g(Index n, const Number* x, bool, Index m, Number* g) {
  Eigen::Map<Eigen::VectorXd> out(g, m);
  problem_.constraintValues(Map(x, n), out);
  return out.allFinite();
}

bool IpoptAdapter::eval_jac_g(Index n, const Number* x, bool, Index, Index nele_jac, Index* iRow,
                              Index* jCol, Number* values) {
  if (values == nullptr) {
    std::copy_n(problem_.jacobianRows().data(), nele_jac, iRow);
    std::copy_n(problem_.jacobianCols().data(), nele_jac, jCol);
    return true;
  }
  problem_.jacobianValues(Map(x, n), values);
  return true;
}

bool IpoptAdapter::eval_h(Index n, const Number* x, bool, Number obj_factor, Index,
                          const Number* lambda, bool, Index nele_hess, Index* iRow, Index* jCol,
                          Number* values) {
  if (!exact_hessian_) return false;
  if (values == nullptr) {
    std::copy_n(problem_.hessianPattern().rows().data(), nele_hess, iRow);
    std::copy_n(problem_.hessianPattern().cols().data(), nele_hess, jCol);
    return true;
  }
  problem_.hessianValues(Map(x, n), obj_factor, lambda, values);
  return true;
}

bool IpoptAdapter::intermediate_callback(Ipopt::AlgorithmMode, Index iter, Number, Number, Number,
                                         Number, Number, Number, Number, Number, Index,
                                         const Ipopt::IpoptData*,
                                         Ipopt::IpoptCalculatedQuantities*) {
  iterations_ = iter;
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
  if (elapsed.count() > max_wall_time_) {
    wall_time_exceeded_ = true;
    return false;
  }
  return cancel_ == nullptr || !cancel_->load();
}

void IpoptAdapter::finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*,
                                     const Number*, Index m, const Number* g, const Number*, Number,
                                     const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) {
  solution_ = Map(x, n);
  Eigen::VectorXd xl, xu, gl, gu;
  problem_.variables().bounds(xl, xu);
  problem_.constraintBounds(gl, gu);
  const Map gv(g, m);
  violation_ = std::max({0.0, (xl - solution_).maxCoeff(), (solution_ - xu).maxCoeff(),
                         m > 0 ? (gl - gv).maxCoeff() : 0.0, m > 0 ? (gv - gu).maxCoeff() : 0.0});
}

}  // namespace rbsf::trajopt
