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

namespace {

/// How the sliding contacts of a balance are taken: each one's planned slip, the kinetic
/// coefficient, and the slip above which the kinetic friction acts (its sign set by the slip).
struct Sliding {
  const VecC& slip;
  double mu;
  double min_slip;

  /// Whether finger i of `set` slides with kinetic friction.
  bool kinetic(const ContactSet& set, int i) const {
    return !set.sticks(i) && mu > 0.0 && std::abs(slip[i]) > min_slip;
  }
};

/// The force unknowns' columns of a set's balance: N (the normal of each touching finger,
/// less its kinetic friction when it slides, then the tangent of each sticking one), each
/// column's finger and, for a tangent, its normal's column (-1 for a normal).
struct ForceColumns {
  Eigen::MatrixXd N;
  Eigen::VectorXi finger, normal_col;
};

/// The columns of `set`'s nt touching fingers and their sticking tangents (nl in all) among
/// `m` fingers, from the contact columns in `data`.
ForceColumns forceColumns(const ContactSet& set, const ModelData& data, const Sliding& sliding,
                          int m, int nq, int nt, int nl) {
  ForceColumns cols{Eigen::MatrixXd(nq, nl), Eigen::VectorXi(nl), Eigen::VectorXi(nl)};
  Eigen::MatrixXd& N = cols.N;
  int c = 0;
  for (int i = 0; i < m; ++i) {
    if (!set.touches(i)) continue;
    N.col(c) = data.G1.col(i);
    if (sliding.kinetic(set, i))
      N.col(c) -= sliding.mu * (sliding.slip[i] > 0.0 ? 1.0 : -1.0) * data.T.col(i);
    cols.normal_col[c] = -1;
    cols.finger[c++] = i;
  }
  for (int j = 0; j < nt; ++j) {
    const int i = cols.finger[j];
    if (!set.sticks(i)) continue;
    N.col(c) = data.T.col(i);
    cols.normal_col[c] = j;
    cols.finger[c++] = i;
  }
  return cols;
}

/// A basis of the force combinations the actuators cannot feel (the null space of N, by
/// its singular values above 1e-9 of the largest).
Eigen::MatrixXd internalSqueezes(const Eigen::MatrixXd& N, int nl) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(N, Eigen::ComputeFullV);
  const auto& sv = svd.singularValues();
  int rank = 0;
  while (rank < sv.size() && sv[rank] > 1e-9 * sv[0]) ++rank;
  return svd.matrixV().rightCols(nl - rank);
}

/// The equality rows over the nx unknowns: the object rows of N, then Z^T z = 0.
Eigen::MatrixXd equalityRows(const Eigen::MatrixXd& N, const Eigen::MatrixXd& Z, int nl, int nx) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(layout::kObjectDim + Z.cols(), nx);
  A.topLeftCorner(layout::kObjectDim, nl) = N.topRows(layout::kObjectDim);
  A.bottomLeftCorner(Z.cols(), nl) = Z.transpose();
  return A;
}

/// The margin rows of G x >= h from row 0: each normal force at least normal_margin times
/// the part's `weight` plus sigma, each sticking tangent within `cone` times its normal force
/// (the friction used of the static cone) less sigma; returns the next row.
int marginRows(const ForceColumns& cols, int nt, int nl, double weight, double normal_margin,
               double cone, Eigen::MatrixXd& G, Eigen::VectorXd& h) {
  int r = 0;
  for (int j = 0; j < nt; ++j, ++r) {
    G(r, j) = 1.0;
    G(r, nl) = -weight;
    h[r] = normal_margin * weight;
  }
  for (int j = nt; j < nl; ++j)
    for (double sign : {-1.0, 1.0}) {
      G(r, cols.normal_col[j]) = cone;
      G(r, j) = sign;
      G(r, nl) = -weight;
      ++r;
    }
  return r;
}

/// The input-limit rows of G x >= h from row r: tau_j = b_row - N_row lambda within
/// [-limit, limit], both sides.
void limitRows(const Eigen::MatrixXd& N, const Eigen::VectorXd& b, int nl, int nu, const Cell& cell,
               int r, Eigen::MatrixXd& G, Eigen::VectorXd& h) {
  for (int j = 0; j < nu; ++j) {
    const int row = layout::inputToConfig(j);
    const double limit = cell.inputLimit(j);
    // tau_j = b_row - N_row lambda within [-limit, limit].
    G.row(r).head(nl) = N.row(row);
    h[r++] = b[row] - limit;
    G.row(r).head(nl) = -N.row(row);
    h[r++] = -b[row] - limit;
  }
}

/// The LP of the balance: maximise sigma (unknown nl, bounded so that the LP is) with the
/// nt normal forces non-negative, subject to the equalities and G x >= h.
SolveStatus maximiseMargin(const Eigen::MatrixXd& A_eq, const Eigen::VectorXd& b_eq,
                           const Eigen::MatrixXd& G, const Eigen::VectorXd& h, int nt, int nl,
                           Eigen::VectorXd& x) {
  const int nx = nl + 1;
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(nx, -inf), upper(nx);
  upper.setConstant(inf);
  for (int j = 0; j < nt; ++j) lower[j] = 0.0;
  lower[nl] = -10.0;  // sigma is bounded so that the LP is
  upper[nl] = 10.0;
  Eigen::VectorXd cost = Eigen::VectorXd::Zero(nx);
  cost[nl] = -1.0;
  return solveLp(cost, A_eq, b_eq, G, h, lower, upper, x);
}

/// The solved balance into `out`: margin, the forces per finger (the sliders' friction
/// along t_i) and the input b - N lambda that applies them.
void storeForces(const Eigen::VectorXd& x, const ForceColumns& cols, const Eigen::VectorXd& b,
                 const ContactSet& set, const Sliding& sliding, int m, int nt, int nl, int nu,
                 ContactBalance& out) {
  out.solvable = true;
  out.margin = x[nl];
  out.balanced = out.margin >= 0.0;
  Eigen::VectorXd lambda = x.head(nl);
  for (int j = 0; j < nl; ++j) (j < nt ? out.fn : out.ft)[cols.finger[j]] = lambda[j];
  for (int i = 0; i < m; ++i)  // friction of the sliding contacts, along t_i
    if (set.touches(i) && sliding.kinetic(set, i))
      out.ft[i] = -sliding.mu * (sliding.slip[i] > 0.0 ? 1.0 : -1.0) * out.fn[i];
  const Eigen::VectorXd gen = b - cols.N * lambda;
  for (int j = 0; j < nu; ++j) out.tau[j] = gen[layout::inputToConfig(j)];
}

}  // namespace

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
  const Sliding sliding{slip, mu_slide, min_slip};
  const ForceColumns cols = forceColumns(set, data, sliding, m, nq, nt, nl);
  MatQQ M;
  model_.massMatrix(q, M);
  const Eigen::VectorXd b = M * vdot + data.bias;  // = u + N lambda

  // Equalities: the object rows and, by the plant's rule, no force combination that the
  // actuators cannot feel (N z = 0: an internal squeeze the least-norm rule leaves at zero).
  Eigen::MatrixXd Z(nl, 0);
  if (settings_.least_norm) Z = internalSqueezes(cols.N, nl);
  const Eigen::MatrixXd A_eq = equalityRows(cols.N, Z, nl, nx);
  Eigen::VectorXd b_eq = Eigen::VectorXd::Zero(A_eq.rows());
  b_eq.head(layout::kObjectDim) = b.head(layout::kObjectDim);

  // Inequalities G x >= h: margins, then the input limits on both sides.
  const int n_margin = nt + 2 * ns;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n_margin + 2 * nu, nx);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(n_margin + 2 * nu);
  const double cone = settings_.friction_use * cell.friction.mu_static;
  const int r = marginRows(cols, nt, nl, weight_, settings_.normal_margin, cone, G, h);
  limitRows(cols.N, b, nl, nu, cell, r, G, h);

  Eigen::VectorXd x;
  if (maximiseMargin(A_eq, b_eq, G, h, nt, nl, x) != SolveStatus::kOptimal) return out;
  storeForces(x, cols, b, set, sliding, m, nt, nl, nu, out);
  return out;
}

}  // namespace rbsf
