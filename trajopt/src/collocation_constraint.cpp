#include "rbsf/trajopt/collocation_constraint.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace rbsf::trajopt {

using layout::kTheta;
using layout::stroke;

namespace {
/// Per contact: the 5 wrench rows (x, y, phi, theta, l_i) of r by its 6 local variables.
constexpr int kWrenchRows = 5, kWrenchVars = 6, kWrenchGradSize = kWrenchRows * kWrenchVars;
}  // namespace

CollocationConstraint::CollocationConstraint(const RbsfModel& model, const DecisionLayout& layout,
                                             const Schedule& schedule)
    : model_(model),
      layout_(layout),
      schedule_(schedule),
      n_(model.configDim()),
      inv_weight_(1.0 / (model.cell().object.mass * std::max(model.cell().gravity, 1.0))) {
  for (const PhaseRun& run : schedule_.runs) hbar_.push_back(run.duration / run.intervals);
  // Structure: AutoDiff at a generic point; an entry is structural when its derivative is
  // non-zero there (random values make accidental zeros a measure-zero event).
  const int L = localSize();
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> uni(0.2, 1.0);
  std::vector<ADScalar> local(L);
  for (int c = 0; c < L; ++c) local[c] = ADScalar(uni(rng), L, c);
  ConfigVector<ADScalar> out;
  defect<ADScalar>(local.data(), 0, out);
  for (int r = 0; r < 2 * n_; ++r)
    for (int c = 0; c < L; ++c)
      if (out[r].derivatives().size() == L && out[r].derivatives()[c] != 0.0)
        local_pattern_.emplace_back(r, c);
  const int ks = layout_.knotSize();
  for (int k = 0; k < layout_.intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    for (const auto& [r, c] : local_pattern_) {
      const int col = c < ks ? layout_.knot(k) + c
                             : (c < 2 * ks ? layout_.knot(k + 1) + c - ks : layout_.duration(j));
      structure_.emplace_back(2 * n_ * k + r, col);
    }
  }
}

void CollocationConstraint::bounds(VectorRef lower, VectorRef upper) const {
  lower.setZero();
  upper.setZero();
}

void CollocationConstraint::gather(const ConstVectorRef& z, int k, double* local) const {
  const int ks = layout_.knotSize();
  for (int c = 0; c < 2 * ks; ++c) local[c] = z[layout_.knot(k) + c];
  local[2 * ks] = z[layout_.duration(schedule_.run_of_interval[k])];
}

void CollocationConstraint::values(const ConstVectorRef& z, VectorRef g) const {
  double local[kMaxLocal];
  ConfigVector<double> out;
  for (int k = 0; k < layout_.intervals(); ++k) {
    gather(z, k, local);
    defect<double>(local, k, out);
    g.segment(2 * n_ * k, 2 * n_) = out;
  }
}

void CollocationConstraint::jacobian(const ConstVectorRef& z, double* values) const {
  const int L = localSize();
  double plain[kMaxLocal];
  local_ad_.resize(L);  // once per solve: L AutoDiff scalars are too big for the stack
  ConfigVector<ADScalar> out;
  std::size_t e = 0;
  for (int k = 0; k < layout_.intervals(); ++k) {
    gather(z, k, plain);
    for (int c = 0; c < L; ++c) local_ad_[c] = ADScalar(plain[c], L, c);
    defect<ADScalar>(local_ad_.data(), k, out);
    for (const auto& [r, c] : local_pattern_) {
      const auto& d = out[r].derivatives();
      values[e++] = d.size() == L ? d[c] : 0.0;
    }
  }
}

void CollocationConstraint::hessianStructure(HessianPattern& p) {
  const int m = model_.numFingers(), ks = layout_.knotSize();
  hess_slots_.clear();
  interval_cols_.clear();
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < ks; ++c)
      if (c != layout::kX && c != layout::kY) interval_cols_.push_back(e * ks + c);
  knot_mu_.assign(static_cast<std::size_t>(layout_.knots()) * n_, 0.0);
  wrench_grad_.assign(static_cast<std::size_t>(layout_.knots()) * m * kWrenchGradSize, 0.0);
  for (int kk = 0; kk < layout_.knots(); ++kk) {  // contact wrenches, once per knot
    for (int i = 0; i < m; ++i) {
      int c6[kWrenchVars];
      wrenchColumns(kk, i, c6);
      for (int a = 0; a < kWrenchVars; ++a)
        for (int b = 0; b <= a; ++b) hess_slots_.push_back(p.slot(c6[a], c6[b]));
    }
  }
  for (int k = 0; k < layout_.intervals(); ++k) {
    for (int e = 0; e < 2; ++e) {
      const int kk = k + e, oq = layout_.q(kk), ov = layout_.v(kk);
      hess_slots_.push_back(p.slot(oq + kTheta, oq + kTheta));  // bias Q
      for (int i = 0; i < m; ++i) {
        hess_slots_.push_back(p.slot(oq + kTheta, oq + stroke(i)));
        hess_slots_.push_back(p.slot(oq + stroke(i), ov + stroke(i)));
        hess_slots_.push_back(p.slot(oq + stroke(i), ov + kTheta));
        hess_slots_.push_back(p.slot(ov + stroke(i), ov + kTheta));
      }
      hess_slots_.push_back(p.slot(ov + kTheta, ov + kTheta));
      for (int i = 0; i < m; ++i) {  // D_v's mass matrix
        hess_slots_.push_back(p.slot(oq + stroke(i), oq + stroke(i)));
        hess_slots_.push_back(p.slot(oq + stroke(i), layout_.v(k) + kTheta));
        hess_slots_.push_back(p.slot(oq + stroke(i), layout_.v(k + 1) + kTheta));
      }
    }
    const int oq = layout_.q(k);
    for (int i = 0; i < m; ++i) {  // D_q's mass matrix M(q_k)
      hess_slots_.push_back(p.slot(oq + stroke(i), oq + stroke(i)));
      hess_slots_.push_back(p.slot(oq + stroke(i), layout_.q(k + 1) + kTheta));
      hess_slots_.push_back(p.slot(oq + stroke(i), oq + kTheta));
      hess_slots_.push_back(p.slot(oq + stroke(i), layout_.v(k) + kTheta));
    }
    const int T = layout_.duration(schedule_.run_of_interval[k]);
    hess_slots_.push_back(p.slot(T, T));
    for (int c : interval_cols_) hess_slots_.push_back(p.slot(T, layout_.knot(k) + c));
  }
}

CollocationConstraint::IntervalScales CollocationConstraint::intervalMultipliers(
    const ConstVectorRef& z, const double* lambda, int k, double* mu0, double* nu0,
    double* mu1) const {
  const int j = schedule_.run_of_interval[k];
  const double inv_hbar = 1.0 / hbar_[j];
  IntervalScales s;
  s.N = schedule_.runs[j].intervals;
  s.h = z[layout_.duration(j)] / s.N;
  s.cq = inv_hbar * inv_hbar * inv_weight_;
  s.cv = inv_hbar * inv_weight_;
  const double* lq = lambda + 2 * n_ * k;  // D_q's multipliers; D_v's follow
  // Knot k's r enters D_q (h^2/2) and D_v (h/2); knot k+1's only D_v.
  for (int a = 0; a < n_; ++a) {
    mu1[a] = s.cv * lq[n_ + a];
    mu0[a] = mu1[a] + s.h * s.cq * lq[a];
    nu0[a] = mu1[a] + 2.0 * s.h * s.cq * lq[a];
  }
  return s;
}

void CollocationConstraint::wrenchColumns(int kk, int i, int* cols) const {
  const int oq = layout_.q(kk);
  cols[0] = oq + layout::kPhi;
  cols[1] = oq + kTheta;
  cols[2] = oq + stroke(i);
  cols[3] = layout_.fn(kk) + i;
  cols[4] = layout_.ft(kk) + i;
  cols[5] = layout_.xi(kk) + i;
}

void CollocationConstraint::contactHessian(const ConstVectorRef& z, int kk, const int*& slot,
                                           double* values) const {
  const int m = model_.numFingers();
  const double* mu = knot_mu_.data() + static_cast<std::size_t>(kk) * n_;
  for (int i = 0; i < m; ++i) {
    int c6[kWrenchVars];
    wrenchColumns(kk, i, c6);
    double x[kWrenchVars];
    for (int a = 0; a < kWrenchVars; ++a) x[a] = z[c6[a]];
    AD6x2 v[kWrenchVars], w[kWrenchRows];
    seedSecondOrder(x, v);
    contactWrench<AD6x2>(model_, i, v[0], v[1], v[2], v[3], v[4], v[5], w);
    const AD6x2 phi = mu[layout::kX] * w[0] + mu[layout::kY] * w[1] + mu[layout::kPhi] * w[2] +
                      mu[kTheta] * w[3] + mu[stroke(i)] * w[4];
    double* g = wrench_grad_.data() + (static_cast<std::size_t>(kk) * m + i) * kWrenchGradSize;
    for (int b = 0; b < kWrenchRows; ++b)
      for (int a = 0; a < kWrenchVars; ++a) g[kWrenchVars * b + a] = w[b].value().derivatives()[a];
    for (int a = 0; a < kWrenchVars; ++a)
      for (int b = 0; b <= a; ++b) values[*slot++] += phi.derivatives()[a].derivatives()[b];
  }
}

void CollocationConstraint::knotHessian(const ConstVectorRef& z, int k, int kk, const double* mu,
                                        const double* nu, double scale, const int*& slot,
                                        double* values, double* grad) const {
  const Cell& cell = model_.cell();
  const int m = model_.numFingers(), oq = layout_.q(kk), ov = layout_.v(kk);
  const int o = layout_.knot(k);        // grad covers knots k and k+1
  const int go = layout_.knot(kk) - o;  // knot kk's block inside grad
  // Contact wrenches' gradient (their Hessian is contactHessian's).
  for (int i = 0; i < m; ++i) {
    const int rows[kWrenchRows] = {layout::kX, layout::kY, layout::kPhi, kTheta, stroke(i)};
    int c6[kWrenchVars];
    wrenchColumns(kk, i, c6);
    const double* g =
        wrench_grad_.data() + (static_cast<std::size_t>(kk) * m + i) * kWrenchGradSize;
    for (int b = 0; b < kWrenchRows; ++b) {
      const double nb = nu[rows[b]];
      for (int a = 0; a < kWrenchVars; ++a) grad[c6[a] - o] += nb * g[kWrenchVars * b + a];
    }
  }
  // Bias: P = mu^T Q (docs/model.md "Dynamics"); r contains -Q.
  const double g0 = cell.gravity, th = z[oq + kTheta], thd = z[ov + kTheta];
  const double ct = std::cos(th), st = std::sin(th), mt = mu[kTheta], nt = nu[kTheta];
  double P_tt = 0.0, P_tdtd = 0.0;
  for (int i = 0; i < m; ++i) {
    const FingerParams& f = cell.fingers[i];
    P_tt += mt * f.mass * g0 * (-f.r * ct + (z[oq + stroke(i)] + f.com_offset) * st) -
            mu[stroke(i)] * f.mass * g0 * ct;
  }
  values[*slot++] -= scale * P_tt;
  double dP_t = 0.0, dP_td = 0.0;
  for (int i = 0; i < m; ++i) {
    const FingerParams& f = cell.fingers[i];
    const double L = z[oq + stroke(i)] + f.com_offset, ld = z[ov + stroke(i)];
    const double mi = mu[stroke(i)], ni = nu[stroke(i)];
    values[*slot++] -= scale * (-mt * f.mass * g0 * ct);
    values[*slot++] -= scale * (2.0 * mt * f.mass * thd);
    values[*slot++] -= scale * (2.0 * mt * f.mass * ld - 2.0 * mi * f.mass * thd);
    values[*slot++] -= scale * (2.0 * mt * f.mass * L);
    P_tdtd -= 2.0 * mi * f.mass * L;
    dP_t += nt * f.mass * g0 * (-f.r * st - L * ct) - ni * f.mass * g0 * st;
    dP_td += 2.0 * nt * f.mass * L * ld - 2.0 * ni * f.mass * L * thd;
    grad[go + stroke(i)] -=
        nt * (2.0 * f.mass * ld * thd - f.mass * g0 * st) - ni * f.mass * thd * thd;
    grad[go + layout_.localV() + stroke(i)] -= 2.0 * nt * f.mass * L * thd;
  }
  values[*slot++] -= scale * P_tdtd;
  grad[go + kTheta] -= dP_t;
  grad[go + layout_.localV() + kTheta] -= dP_td;
  for (int j = 0; j < layout::controlDim(m); ++j)
    grad[go + layout_.localTau() + j] += nu[layout::inputToConfig(j)];
}

void CollocationConstraint::addHessian(const ConstVectorRef& z, const double* lambda,
                                       double* values) const {
  const Cell& cell = model_.cell();
  const int m = model_.numFingers(), ks = layout_.knotSize();
  const int* slot = hess_slots_.data();
  double mu0[kMaxConfig], nu0[kMaxConfig], mu1[kMaxConfig];
  // Each knot's wrench multiplier: the -h/2 mu of the one or two intervals sharing it.
  std::fill(knot_mu_.begin(), knot_mu_.end(), 0.0);
  for (int k = 0; k < layout_.intervals(); ++k) {
    const double h = intervalMultipliers(z, lambda, k, mu0, nu0, mu1).h;
    for (int a = 0; a < n_; ++a) {
      knot_mu_[static_cast<std::size_t>(k) * n_ + a] -= 0.5 * h * mu0[a];
      knot_mu_[static_cast<std::size_t>(k + 1) * n_ + a] -= 0.5 * h * mu1[a];
    }
  }
  for (int kk = 0; kk < layout_.knots(); ++kk) contactHessian(z, kk, slot, values);

  double grad[kMaxLocal];
  double local[kMaxLocal];
  ConfigVector<double> r0, lq_vec(n_), Mlq;
  for (int k = 0; k < layout_.intervals(); ++k) {
    const auto [N, h, cq, cv] = intervalMultipliers(z, lambda, k, mu0, nu0, mu1);
    const double* lq = lambda + 2 * n_ * k;
    const double dv_theta = z[layout_.v(k + 1) + kTheta] - z[layout_.v(k) + kTheta];
    std::fill(grad, grad + 2 * ks, 0.0);
    for (int e = 0; e < 2; ++e) {
      const int kk = k + e, oq = layout_.q(kk);
      knotHessian(z, k, kk, e == 0 ? mu0 : mu1, e == 0 ? nu0 : mu1, -0.5 * h, slot, values, grad);
      for (int i = 0; i < m; ++i) {  // D_v's 1/2 (M_k + M_k+1) dv
        const FingerParams& f = cell.fingers[i];
        const double L = z[oq + stroke(i)] + f.com_offset, c = cv * lq[n_ + kTheta] * f.mass;
        values[*slot++] += c * dv_theta;
        values[*slot++] -= c * L;
        values[*slot++] += c * L;
      }
    }
    // grad: gradient of nu^T r over both knots; the T_j column is its -1/(2 N) multiple
    // plus the gradient of d/dT (c_q lambda_q^T M(q_k) (-h v_k)) = -c_q/N lambda_q^T M v_k.
    for (int c = 0; c < 2 * ks; ++c) grad[c] *= -0.5 / N;
    gather(z, k, local);
    for (int a = 0; a < n_; ++a) lq_vec[a] = lq[a];
    massTimes<double>(cell, local, 0, lq_vec, Mlq);
    for (int a = 0; a < n_; ++a) grad[layout_.localV() + a] -= cq / N * Mlq[a];
    const int oq = layout_.q(k), ov = layout_.v(k);
    const double dq_theta = z[layout_.q(k + 1) + kTheta] - z[oq + kTheta] - h * z[ov + kTheta];
    for (int i = 0; i < m; ++i) {  // D_q's M(q_k) (q_k+1 - q_k - h v_k), M_theta,theta's L_i^2
      const FingerParams& f = cell.fingers[i];
      const double L = z[oq + stroke(i)] + f.com_offset, c = cq * lq[kTheta] * f.mass;
      values[*slot++] += 2.0 * c * dq_theta;
      values[*slot++] += 2.0 * c * L;
      values[*slot++] -= 2.0 * c * L;
      values[*slot++] -= 2.0 * c * L * h;
      grad[stroke(i)] -= 2.0 * c * L * z[ov + kTheta] / N;
    }
    knotRhs<double>(model_, layout_, local, 0, r0);
    double lr = 0.0;
    for (int a = 0; a < n_; ++a) lr += lq[a] * r0[a];
    values[*slot++] -= cq / (static_cast<double>(N) * N) * lr;  // T_j, T_j
    for (int c : interval_cols_) values[*slot++] += grad[c];
  }
}

}  // namespace rbsf::trajopt
