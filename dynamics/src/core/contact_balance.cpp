#include "rbsf/dynamics/core/contact_balance.h"

#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "rbsf/dynamics/core/small_solvers.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

int ContactSet::bitCount(std::uint32_t bits) {
  int n = 0;
  for (; bits != 0; bits >>= 1) n += static_cast<int>(bits & 1u);
  return n;
}

int ContactSet::pivot() const {
  if (stickingCount() != 1) return -1;
  int i = 0;
  while (!sticks(i)) ++i;
  return i;
}

Phase ContactSet::phase() const {
  const int s = stickingCount();
  return s == 0 ? Phase::kU : s == 1 ? Phase::kP : Phase::kC;
}

ContactBalancer::ContactBalancer(const RbsfModel& model, BalanceSettings settings)
    : model_(model),
      settings_(settings),
      weight_(model.cell().object.mass * std::max(model.cell().gravity, 1e-9)) {}

ContactBalance ContactBalancer::solve(const VecQ& q, const VecQ& v, const VecQ& vdot,
                                      const ContactSet& set, ModelData& data) const {
  model_.updateContacts(q, data);
  model_.bias(q, v, data.bias);
  const int m = model_.numFingers();
  VecC slip = VecC::Zero(m);
  for (int i = 0; i < m; ++i) slip[i] = data.T.col(i).dot(v);
  return solveWith(q, vdot, set, data, slip, model_.cell().friction.mu_kinetic,
                   settings_.slip_rate);
}

ContactBalance ContactBalancer::statics(const VecQ& q, const ContactSet& set, ModelData& data,
                                        const VecC& slip) const {
  return atRest(q, set, data, slip, model_.cell().friction.mu_kinetic, settings_.slip_rate);
}

ContactBalance ContactBalancer::breakaway(const VecQ& q, const ContactSet& set, ModelData& data,
                                          const VecC& slip) const {
  // Any slip at all must first break the contact loose: the smallest one counts.
  return atRest(q, set, data, slip, settings_.breakaway * model_.cell().friction.mu_static, 1e-9);
}

ContactBalance ContactBalancer::atRest(const VecQ& q, const ContactSet& set, ModelData& data,
                                       const VecC& slip, double mu_slide, double min_slip) const {
  model_.updateContacts(q, data);
  const VecQ zero = VecQ::Zero(q.size());
  model_.bias(q, zero, data.bias);
  const VecC s = slip.size() == model_.numFingers() ? slip : VecC::Zero(model_.numFingers());
  return solveWith(q, zero, set, data, s, mu_slide, min_slip);
}

bool ContactBalancer::determined(const ContactSet& set, const ModelData& data) const {
  if (set.rows() < 3) return false;
  const double L = model_.shape().boundingRadius();
  Eigen::MatrixXd rows(3, set.rows());
  int c = 0;
  auto add = [&](const auto& column) {
    rows(0, c) = column[layout::kX];
    rows(1, c) = column[layout::kY];
    rows(2, c) = column[layout::kPhi] / L;
    ++c;
  };
  for (int i = 0; i < model_.numFingers(); ++i) {
    if (!set.touches(i)) continue;
    add(data.G1.col(i));
    if (set.sticks(i)) add(data.T.col(i));
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(rows);
  const auto& s = svd.singularValues();
  return s[0] > 0.0 && s[2] >= settings_.determined_ratio * s[0];
}

ContactBalance ContactBalancer::solveWith(const VecQ& q, const VecQ& vdot, const ContactSet& set,
                                          const ModelData& data, const VecC& slip, double mu_slide,
                                          double min_slip) const {
  const int m = model_.numFingers(), nq = model_.configDim(), nu = model_.controlDim();
  const Cell& cell = model_.cell();
  ContactBalance out;
  out.fn = VecC::Zero(m);
  out.ft = VecC::Zero(m);
  out.tau = VecU::Zero(nu);
  out.margin = -std::numeric_limits<double>::infinity();
  out.determined = determined(set, data);

  // Unknowns x = (f_n of each touching finger, f_t of each sticking one, sigma).
  const int nt = set.count(), ns = set.stickingCount(), nl = nt + ns, nx = nl + 1;
  if (nt == 0) return out;
  Eigen::MatrixXd N(nq, nl);
  Eigen::VectorXi finger(nl), normal_col(nl);  // normal_col: a tangent's normal column
  int c = 0;
  auto kinetic = [&](int i) {
    return !set.sticks(i) && mu_slide > 0.0 && std::abs(slip[i]) > min_slip;
  };
  for (int i = 0; i < m; ++i) {
    if (!set.touches(i)) continue;
    N.col(c) = data.G1.col(i);
    if (kinetic(i)) N.col(c) -= mu_slide * (slip[i] > 0.0 ? 1.0 : -1.0) * data.T.col(i);
    normal_col[c] = -1;
    finger[c++] = i;
  }
  for (int j = 0; j < nt; ++j) {
    const int i = finger[j];
    if (!set.sticks(i)) continue;
    N.col(c) = data.T.col(i);
    normal_col[c] = j;
    finger[c++] = i;
  }
  MatQQ M;
  model_.massMatrix(q, M);
  const Eigen::VectorXd b = M * vdot + data.bias;  // = u + N lambda

  // Equalities: the object rows and, by the plant's rule, no force combination that the
  // actuators cannot feel (N z = 0: an internal squeeze the least-norm rule leaves at zero).
  Eigen::MatrixXd Z(nl, 0);
  if (settings_.least_norm) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(N, Eigen::ComputeFullV);
    const auto& sv = svd.singularValues();
    int rank = 0;
    while (rank < sv.size() && sv[rank] > 1e-9 * sv[0]) ++rank;
    Z = svd.matrixV().rightCols(nl - rank);
  }
  const Eigen::MatrixXd A_eq = [&] {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(layout::kObjectDim + Z.cols(), nx);
    A.topLeftCorner(layout::kObjectDim, nl) = N.topRows(layout::kObjectDim);
    A.bottomLeftCorner(Z.cols(), nl) = Z.transpose();
    return A;
  }();
  Eigen::VectorXd b_eq = Eigen::VectorXd::Zero(A_eq.rows());
  b_eq.head(layout::kObjectDim) = b.head(layout::kObjectDim);

  // Inequalities G x >= h: margins, then the input limits on both sides.
  const int n_margin = nt + 2 * ns;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n_margin + 2 * nu, nx);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(n_margin + 2 * nu);
  int r = 0;
  for (int j = 0; j < nt; ++j, ++r) {
    G(r, j) = 1.0;
    G(r, nl) = -weight_;
    h[r] = settings_.normal_margin * weight_;
  }
  const double cone = settings_.friction_use * cell.friction.mu_static;
  for (int j = nt; j < nl; ++j)
    for (double sign : {-1.0, 1.0}) {
      G(r, normal_col[j]) = cone;
      G(r, j) = sign;
      G(r, nl) = -weight_;
      ++r;
    }
  for (int j = 0; j < nu; ++j) {
    const int row = layout::inputToConfig(j);
    const double limit = cell.inputLimit(j);
    // tau_j = b_row - N_row lambda within [-limit, limit].
    G.row(r).head(nl) = N.row(row);
    h[r++] = b[row] - limit;
    G.row(r).head(nl) = -N.row(row);
    h[r++] = -b[row] - limit;
  }

  const double inf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(nx, -inf), upper(nx);
  upper.setConstant(inf);
  for (int j = 0; j < nt; ++j) lower[j] = 0.0;
  lower[nl] = -10.0;  // sigma is bounded so that the LP is
  upper[nl] = 10.0;
  Eigen::VectorXd cost = Eigen::VectorXd::Zero(nx), x;
  cost[nl] = -1.0;
  if (solveLp(cost, A_eq, b_eq, G, h, lower, upper, x) != SolveStatus::kOptimal) return out;

  out.solvable = true;
  out.margin = x[nl];
  out.balanced = out.margin >= 0.0;
  Eigen::VectorXd lambda = x.head(nl);
  for (int j = 0; j < nl; ++j) (j < nt ? out.fn : out.ft)[finger[j]] = lambda[j];
  for (int i = 0; i < m; ++i)  // friction of the sliding contacts, along t_i
    if (set.touches(i) && kinetic(i))
      out.ft[i] = -mu_slide * (slip[i] > 0.0 ? 1.0 : -1.0) * out.fn[i];
  const Eigen::VectorXd gen = b - N * lambda;
  for (int j = 0; j < nu; ++j) out.tau[j] = gen[layout::inputToConfig(j)];
  return out;
}

}  // namespace rbsf
