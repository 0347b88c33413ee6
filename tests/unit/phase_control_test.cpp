// Inverse dynamics by phase: every tau is checked by running it through the forward
// dynamics of its phase (solvePhaseC, forwardDynamicsU), by the equations of motion, by a
// closed-form rigid-motion acceleration, and against the older analyses it generalises.
#include <gtest/gtest.h>

#include <vector>

#include <Eigen/SVD>

#include "rbsf/dynamics/forward_dynamics.h"
#include "rbsf/dynamics/holding.h"
#include "rbsf/dynamics/phase_control.h"
#include "rbsf/dynamics/rotation_analysis.h"
#include "test_support.h"

namespace rbsf {
namespace {

using test::ShapeKind;

Cell defaultCell() { return loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"); }

// A random velocity in the null space of the rows of C (every such row stays zero).
VecQ nullSpaceVelocity(const Eigen::MatrixXd& C, std::mt19937& rng, double scale) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const Eigen::MatrixXd null = svd.matrixV().rightCols(C.cols() - svd.rank());
  return null * test::randomVector(static_cast<int>(null.cols()), rng, scale);
}

// Sticking velocity: base rotation and common stroke (G1^T v = T^T v = 0).
VecQ stickingVelocity(const ModelData& d, std::mt19937& rng) {
  Eigen::MatrixXd C(2 * d.m, d.G1.rows());
  C << d.G1.transpose(), d.T.transpose();
  return nullSpaceVelocity(C, rng, 0.5);
}

// Closed contacts that may slide (G1^T v = 0).
VecQ closedVelocity(const ModelData& d, std::mt19937& rng) {
  return nullSpaceVelocity(d.G1.transpose(), rng, 0.5);
}

// Phase C from the kinematics alone: the part is fixed in a frame that turns with the
// base and slides along the base y axis by the common stroke s. With w = R(-theta) x_o,
// w' = (0, s'), w'' = (0, s''):
//   x_o'' = R(theta) (w'' + 2 theta' S w' + theta'' S w - theta'^2 w).
VecQ rigidAcceleration(const RbsfModel& model, const VecQ& q, const VecQ& v, double theta_dd,
                       double stroke_dd) {
  const double th = q[layout::kTheta], thd = v[layout::kTheta];
  const Vec2 w = rotate(-th, Vec2(q[layout::kX], q[layout::kY]));
  const Vec2 wd(0.0, v[layout::stroke(0)]), wdd(0.0, stroke_dd);
  const Vec2 a = rotate(th, wdd + 2.0 * thd * perp(wd) + theta_dd * perp(w) - thd * thd * w);
  VecQ out(model.configDim());
  out[layout::kX] = a.x();
  out[layout::kY] = a.y();
  out[layout::kPhi] = theta_dd;
  out[layout::kTheta] = theta_dd;
  for (int i = 0; i < model.numFingers(); ++i) out[layout::stroke(i)] = stroke_dd;
  return out;
}

double uniformIn(const AccelRange& r, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.05, 0.95);
  return r.min + u(rng) * (r.max - r.min);
}

void expectWithinLimits(const RbsfModel& model, const VecU& tau) {
  EXPECT_LE(std::abs(tau[layout::kTauTheta]), model.cell().base.torque_limit);
  for (int i = 0; i < model.numFingers(); ++i) {
    EXPECT_LE(std::abs(tau[layout::fingerForce(i)]), model.cell().fingers[i].force_limit);
  }
}

// M dv/dt + Q = u + G1 F_n + T F_t, relative to the size of the terms.
double motionResidual(const RbsfModel& model, const VecQ& q, const VecQ& v, const ModelData& d,
                      const PhaseControlResult& r) {
  MatQQ M;
  VecQ Q, u;
  model.massMatrix(q, M);
  model.bias(q, v, Q);
  model.generalizedInput(r.tau, u);
  const VecQ lhs = M * r.vdot + Q;
  const VecQ rhs = u + d.G1 * r.fn + d.T * r.ft;
  return (lhs - rhs).norm() / (1.0 + lhs.norm() + rhs.norm());
}

// Phase C, its constraints, and the simulator's reading of the returned tau.
void checkPhaseC(const RbsfModel& model, const VecQ& q, const VecQ& v, const ModelData& d,
                 const PhaseControlOptions& opt, double theta_dd, double stroke_dd,
                 const PhaseControlResult& r) {
  const int m = model.numFingers();
  const double mu = model.cell().friction.mu_static * (1.0 - opt.friction_margin);
  const double f_min = opt.min_normal_fraction * model.cell().object.mass * model.cell().gravity;
  expectWithinLimits(model, r.tau);
  const double tol = 1e-7 * (1.0 + r.fn.norm());  // the solvers' feasibility tolerance
  for (int i = 0; i < m; ++i) {
    EXPECT_GE(r.fn[i], f_min);
    EXPECT_LE(std::abs(r.ft[i]), mu * r.fn[i] + tol);
  }
  EXPECT_LT(motionResidual(model, q, v, d, r), 1e-9);
  const VecQ rigid = rigidAcceleration(model, q, v, theta_dd, stroke_dd);
  EXPECT_LT((r.vdot - rigid).norm(), 1e-8 * (1.0 + rigid.norm()));

  ModelData e = d;
  const StickSolution s = solvePhaseC(model, q, v, r.tau, e);
  EXPECT_TRUE(s.feasible);
  EXPECT_LT((s.vdot - rigid).norm(), 1e-7 * (1.0 + rigid.norm()));
}

// Phase U through the LCP of the simulator.
void checkPhaseU(const RbsfModel& model, const VecQ& q, const VecQ& v,
                 const PhaseControlOptions& opt, double omega_dd, double theta_dd,
                 const PhaseControlResult& r) {
  const double f_min = opt.min_normal_fraction * model.cell().object.mass * model.cell().gravity;
  expectWithinLimits(model, r.tau);
  ModelData e(model.numFingers());
  forwardDynamicsU(model, q, v, r.tau, e);
  const double scale = 1.0 + e.vdot.norm();
  for (int i = 0; i < model.numFingers(); ++i) {
    EXPECT_GE(e.fn[i], f_min) << "contact " << i << " stays pressed";
    EXPECT_NEAR(e.fn[i], r.fn[i], 1e-6 * (1.0 + std::abs(r.fn[i])));
    EXPECT_LT(std::abs(e.delta_n[i]), 1e-7 * scale);
  }
  EXPECT_NEAR(e.vdot[layout::kPhi], omega_dd, 1e-7 * scale);
  if (!std::isnan(theta_dd)) {
    EXPECT_NEAR(e.vdot[layout::kTheta], theta_dd, 1e-7 * scale);
  }
  EXPECT_LT((e.vdot - r.vdot).norm(), 1e-7 * scale);
}

class PhaseControlTest : public ::testing::TestWithParam<ShapeKind> {};

TEST_P(PhaseControlTest, PhaseCTargetsAreWhatTheStickingDynamicsDo) {
  for (int m : {3, 4}) {
    const RbsfModel model(test::makeCell(GetParam(), m));
    const PhaseControlOptions opt;
    PhaseControl pc(model, opt);
    std::mt19937 rng(31 + m);
    int solved = 0;
    for (int trial = 0; trial < 15; ++trial) {
      const VecQ q = test::randomContactState(model, rng);
      ModelData d(m);
      model.updateContacts(q, d);
      const VecQ v = stickingVelocity(d, rng);
      pc.setState(q, v, d);
      const AccelRange base = pc.rangeCBase();
      if (!base.feasible) continue;
      const double theta_dd = uniformIn(base, rng);
      const AccelRange stroke = pc.rangeCStroke(theta_dd);
      ASSERT_TRUE(stroke.feasible) << "theta'' inside its range admits some s''";
      const double stroke_dd = uniformIn(stroke, rng);
      const PhaseControlResult r = pc.solveC(theta_dd, stroke_dd);
      ASSERT_TRUE(r.feasible) << "the LP's range and the least-norm solve agree";
      ++solved;
      checkPhaseC(model, q, v, d, opt, theta_dd, stroke_dd, r);

      // Past the range's ends the target is infeasible, and a huge one is too.
      const double width = base.max - base.min;
      EXPECT_FALSE(pc.solveC(base.max + 0.01 * width, 0.0).feasible);
      EXPECT_FALSE(pc.solveC(base.min - 0.01 * width, 0.0).feasible);
      EXPECT_FALSE(pc.solveC(1e4, stroke_dd).feasible);
      EXPECT_FALSE(pc.solveC(theta_dd, 1e4).feasible);
    }
    EXPECT_GE(solved, 12) << "m = " << m;
  }
}

TEST_P(PhaseControlTest, PhaseUTargetsAreWhatTheLcpDoes) {
  const RbsfModel model(test::makeCell(GetParam(), 3));
  const PhaseControlOptions opt;
  PhaseControl pc(model, opt);
  std::mt19937 rng(41);
  int solved = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(3);
    model.updateContacts(q, d);
    const VecQ v = closedVelocity(d, rng);
    pc.setState(q, v, d);
    const AccelRange object = pc.rangeUObject();
    if (!object.feasible) continue;
    ++solved;
    const double omega_dd = uniformIn(object, rng);
    const PhaseControlResult r = pc.solveU(omega_dd);
    ASSERT_TRUE(r.feasible);
    checkPhaseU(model, q, v, opt, omega_dd, PhaseControl::kFree, r);

    const AccelRange base = pc.rangeUBase(omega_dd);
    ASSERT_TRUE(base.feasible);
    const double theta_dd = uniformIn(base, rng);
    const PhaseControlResult rb = pc.solveU(omega_dd, theta_dd);
    ASSERT_TRUE(rb.feasible);
    checkPhaseU(model, q, v, opt, omega_dd, theta_dd, rb);

    const double width = object.max - object.min;
    EXPECT_FALSE(pc.solveU(object.max + 0.01 * width).feasible);
    EXPECT_FALSE(pc.solveU(object.min - 0.01 * width).feasible);
    EXPECT_FALSE(pc.solveU(1e5).feasible);
    EXPECT_FALSE(pc.solveU(omega_dd, base.max + 0.01 * (base.max - base.min)).feasible);
  }
  EXPECT_GE(solved, 15);
}

TEST_P(PhaseControlTest, SamplerFractionsGiveCheckedControls) {
  const RbsfModel model(test::makeCell(GetParam(), 3));
  const PhaseControlOptions opt;
  PhaseControl pc(model, opt);
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> frac(-1.0, 1.0);
  int c_ok = 0, u_ok = 0, c_tried = 0, u_tried = 0;
  for (int trial = 0; trial < 15; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(3);
    model.updateContacts(q, d);
    const VecQ v = stickingVelocity(d, rng);
    pc.setState(q, v, d);
    // The extremes are part of what a sampler draws.
    for (double f : {frac(rng), -1.0, 1.0}) {
      const double g = frac(rng);
      if (pc.rangeCBase().feasible) {
        ++c_tried;
        const PhaseControlResult c = pc.sample(Phase::kC, f, g);
        if (c.feasible) {
          ++c_ok;
          checkPhaseC(model, q, v, d, opt, c.vdot[layout::kTheta], c.vdot[layout::stroke(0)], c);
        }
      }
      if (pc.rangeUObject().feasible) {
        ++u_tried;
        const PhaseControlResult u = pc.sample(Phase::kU, f, g);
        if (u.feasible) {
          ++u_ok;
          checkPhaseU(model, q, v, opt, u.vdot[layout::kPhi], u.vdot[layout::kTheta], u);
          // The sticking verdict is solvePhaseC's at this tau.
          ModelData e = d;
          EXPECT_EQ(u.stick_feasible, solvePhaseC(model, q, v, u.tau, e).feasible);
        }
      }
    }
  }
  EXPECT_EQ(c_ok, c_tried);
  EXPECT_EQ(u_ok, u_tried);
  EXPECT_GE(c_tried, 30);
  EXPECT_GE(u_tried, 30);
  EXPECT_THROW(pc.sample(Phase::kP, 0.0, 0.0), std::invalid_argument);
}

// Optimality certificate of a rule (KKT, sufficient for a convex quadratic): x minimises
// sum (x_i / w_i)^2 subject to A x = b, G x >= g iff, with y = x / w, y = (A W)^T mu +
// (G W)_S^T nu with nu >= 0 on the active rows S. Found by NNLS over [G_S^T, A^T, -A^T]
// in y; A, G and g are written by the test from the model, not taken from PhaseControl.
void expectOptimal(const Eigen::MatrixXd& A_x, const Eigen::MatrixXd& G_x, const Eigen::VectorXd& g,
                   const Eigen::VectorXd& x, const Eigen::VectorXd& w) {
  const Eigen::MatrixXd A = A_x * w.asDiagonal(), G = G_x * w.asDiagonal();
  const Eigen::VectorXd y = x.cwiseQuotient(w);
  std::vector<int> active;
  for (int i = 0; i < G.rows(); ++i) {
    const double slack = G.row(i).dot(y) - g[i];
    const double size = 1.0 + std::abs(g[i]) + G.row(i).norm() * y.norm();
    EXPECT_GE(slack, -1e-7 * size) << "row " << i;
    // PhaseControl solves against bounds tightened by 1e-6 of the force limits (rounding
    // guards): count rows that close as active.
    if (slack <= 1e-4 * size) active.push_back(i);
  }
  const int na = static_cast<int>(active.size());
  Eigen::MatrixXd E(y.size(), na + 2 * A.rows());
  for (int k = 0; k < na; ++k) E.col(k) = G.row(active[k]).transpose();
  E.middleCols(na, A.rows()) = A.transpose();
  E.rightCols(A.rows()) = -A.transpose();
  Eigen::VectorXd z;
  ASSERT_TRUE(solveNnls(E, y, z));
  EXPECT_LT((E * z - y).norm(), 1e-6 * y.norm()) << "no multipliers: not the optimum";
}

TEST(PhaseControlRules, PhaseCPicksTheLeastContactForces) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 4));
  const Cell& cell = model.cell();
  const PhaseControlOptions opt;
  const double mu = cell.friction.mu_static * (1.0 - opt.friction_margin);
  const double f_min = opt.min_normal_fraction * cell.object.mass * cell.gravity;
  PhaseControl pc(model, opt);
  std::mt19937 rng(61);
  for (int trial = 0; trial < 5; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(4);
    model.updateContacts(q, d);
    const VecQ v = stickingVelocity(d, rng);
    pc.setState(q, v, d);
    const AccelRange base = pc.rangeCBase(0.0);
    ASSERT_TRUE(base.feasible);
    const PhaseControlResult r = pc.solveC(uniformIn(base, rng), 0.0);
    ASSERT_TRUE(r.feasible);
    Eigen::VectorXd lambda(8);
    lambda << r.fn, r.ft;
    // Other forces with the same accelerations: the object rows fix their resultant and
    // tau follows from the mechanism rows.
    MatQQ M;
    VecQ Q;
    model.massMatrix(q, M);
    model.bias(q, v, Q);
    Eigen::MatrixXd N(model.configDim(), 8);
    N << d.G1, d.T;
    const VecQ load = M * r.vdot + Q;
    // f_n >= f_min, margined cones, and |tau| <= limit with tau = load_R - N_R lambda.
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(12 + 10, 8);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(22);
    for (int i = 0; i < 4; ++i) {
      G(3 * i, i) = 1.0;
      g[3 * i] = f_min;
      G(3 * i + 1, i) = G(3 * i + 2, i) = mu;
      G(3 * i + 1, 4 + i) = -1.0;
      G(3 * i + 2, 4 + i) = 1.0;
    }
    Eigen::VectorXd limit(5);
    limit << cell.base.torque_limit, cell.fingers[0].force_limit, cell.fingers[1].force_limit,
        cell.fingers[2].force_limit, cell.fingers[3].force_limit;
    G.middleRows(12, 5) = N.bottomRows(5);
    g.segment(12, 5) = load.tail(5) - limit;
    G.bottomRows(5) = -N.bottomRows(5);
    g.tail(5) = -load.tail(5) - limit;
    expectOptimal(N.topRows(layout::kObjectDim), G, g, lambda, Eigen::VectorXd::Ones(8));
  }
}

TEST(PhaseControlRules, PhaseUPicksTheLeastNormalisedEffort) {
  const RbsfModel model(test::makeCell(ShapeKind::kSuperellipse, 3));
  const Cell& cell = model.cell();
  const PhaseControlOptions opt;
  const double f_min = opt.min_normal_fraction * cell.object.mass * cell.gravity;
  PhaseControl pc(model, opt);
  std::mt19937 rng(62);
  for (int trial = 0; trial < 5; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(3);
    model.updateContacts(q, d);
    const VecQ v = closedVelocity(d, rng);
    pc.setState(q, v, d);
    const AccelRange object = pc.rangeUObject();
    ASSERT_TRUE(object.feasible);
    const double omega_dd = uniformIn(object, rng);
    const PhaseControlResult r = pc.solveU(omega_dd);
    ASSERT_TRUE(r.feasible);
    // x = (tau, F_n); the equality rows are delta_n = 0 and the omega'' target, written
    // from M dv/dt = u - Q + G1 F_n with dv/dt linear in x.
    Eigen::MatrixXd Minv = Eigen::MatrixXd::Identity(7, 7);
    model.applyMassInverse(q, Minv);
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(7, 7);
    for (int j = 0; j < 4; ++j) B(layout::inputToConfig(j), j) = 1.0;
    B.rightCols(3) = d.G1;
    const Eigen::MatrixXd acc = Minv * B;  // dv/dt = acc x + const
    Eigen::MatrixXd A_eq(4, 7);
    A_eq << d.G1.transpose() * acc, acc.row(layout::kPhi);
    Eigen::VectorXd x(7);
    x << r.tau, r.fn;
    Eigen::VectorXd w(7);
    w << cell.base.torque_limit, cell.fingers[0].force_limit, cell.fingers[1].force_limit,
        cell.fingers[2].force_limit, cell.fingers[0].force_limit, cell.fingers[1].force_limit,
        cell.fingers[2].force_limit;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(11, 7);
    Eigen::VectorXd g(11);
    for (int j = 0; j < 4; ++j) {
      G(2 * j, j) = 1.0;
      G(2 * j + 1, j) = -1.0;
      g[2 * j] = g[2 * j + 1] = -w[j];
    }
    G.bottomRightCorner(3, 3).setIdentity();
    g.tail(3).setConstant(f_min);
    expectOptimal(A_eq, G, g, x, w);
  }
}

TEST(PhaseControlRules, WithoutMarginsPhaseCAtRestIsTheHoldingSolution) {
  // holdingTorques() solves the same problem at rest with plain cones and F_n >= 0.
  const RbsfModel model(test::makeCell(ShapeKind::kCircle, 3));
  PhaseControlOptions opt;
  opt.friction_margin = 0.0;
  opt.min_normal_fraction = 0.0;
  PhaseControl pc(model, opt);
  std::mt19937 rng(63);
  int held = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const VecQ q = test::randomContactState(model, rng);
    ModelData d(3);
    model.updateContacts(q, d);
    const VecQ rest = VecQ::Zero(model.configDim());
    pc.setState(q, rest, d);
    const HoldingSolution h = holdingTorques(model, q, d);
    const PhaseControlResult r = pc.solveC(0.0, 0.0);
    ASSERT_EQ(r.feasible, h.feasible);
    if (!h.feasible) continue;
    ++held;
    EXPECT_LT((r.tau - h.tau).norm(), 1e-6 * (1.0 + h.tau.norm()));
    EXPECT_LT((r.fn - h.fn).norm() + (r.ft - h.ft).norm(), 1e-6 * (1.0 + h.fn.norm()));
    EXPECT_LT(r.vdot.norm(), 1e-9);
  }
  EXPECT_GE(held, 8);
}

TEST(PhaseControlRanges, WithoutMarginsTheObjectRangeIsOmegaDotRange) {
  const RbsfModel model(defaultCell());
  PhaseControlOptions opt;
  opt.min_normal_fraction = 0.0;
  PhaseControl pc(model, opt), pressed(model);
  for (const Pose& pose : {Pose{-0.10, 0.40, -3.10}, Pose{0.05, 0.40, -0.90},
                           Pose{0.15, 0.40, 0.30}, Pose{0.10, 0.40, 0.0}}) {
    const VecQ q = restingConfiguration(model, pose, 0.0);
    ModelData d(3);
    model.updateContacts(q, d);
    VecQ v = VecQ::Zero(7);
    v[layout::kTheta] = 0.3;  // not at rest: velocity products matter
    pc.setState(q, v, d);
    pressed.setState(q, v, d);
    const OmegaDotRange ref = omegaDotRange(model, q, v, d);
    const AccelRange r = pc.rangeUObject();
    ASSERT_EQ(r.feasible, ref.feasible);
    if (!ref.feasible) continue;
    // PhaseControl's rounding guards (limits 1e-6 tighter, F_n >= 1e-6 of the largest
    // finger force limit) move the range by about 1e-3 rad/s^2.
    EXPECT_NEAR(r.min, ref.min, 2e-3 + 2e-6 * std::abs(ref.min));
    EXPECT_NEAR(r.max, ref.max, 2e-3 + 2e-6 * std::abs(ref.max));
    // Keeping every contact pressed costs range.
    const AccelRange p = pressed.rangeUObject();
    if (p.feasible) {
      EXPECT_GE(p.min, r.min - 1e-9);
      EXPECT_LE(p.max, r.max + 1e-9);
      EXPECT_LT(p.max - p.min, r.max - r.min);
    }
  }
}

TEST(PhaseControlDefaultCell, HoldTurnAndRollOnTheDefaultPart) {
  // cells/default.yaml: the ellipse's centre over the middle finger, the COM 0.1 m right.
  const RbsfModel model(defaultCell());
  const PhaseControlOptions opt;
  PhaseControl pc(model, opt);
  const VecQ q = restingConfiguration(model, Pose{0.10, 0.40, 0.0}, 0.0);
  ModelData d(3);
  model.updateContacts(q, d);
  const VecQ rest = VecQ::Zero(7);
  pc.setState(q, rest, d);

  const PhaseControlResult hold = pc.solveC(0.0, 0.0);
  ASSERT_TRUE(hold.feasible);
  checkPhaseC(model, q, rest, d, opt, 0.0, 0.0, hold);
  const AccelRange base = pc.rangeCBase(0.0);
  ASSERT_TRUE(base.feasible);
  EXPECT_LT(base.min, -1.0);
  EXPECT_GT(base.max, 1.0);
  for (double f : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
    for (double g : {-1.0, 0.0, 1.0}) {
      const PhaseControlResult c = pc.sample(Phase::kC, f, g);
      ASSERT_TRUE(c.feasible) << f << " " << g;
      checkPhaseC(model, q, rest, d, opt, c.vdot[layout::kTheta], c.vdot[layout::stroke(0)], c);
      const PhaseControlResult u = pc.sample(Phase::kU, f, g);
      ASSERT_TRUE(u.feasible) << f << " " << g;
      checkPhaseU(model, q, rest, opt, u.vdot[layout::kPhi], u.vdot[layout::kTheta], u);
    }
  }
  // Fraction 0 is "no acceleration" whenever the range allows it.
  const PhaseControlResult still = pc.sample(Phase::kC, 0.0, 0.0);
  EXPECT_LT(still.vdot.norm(), 1e-9);
  // A fraction scales the extreme in its direction (the range holds 0 here).
  const AccelRange object = pc.rangeUObject();
  ASSERT_TRUE(object.feasible);
  ASSERT_LT(object.min, 0.0);
  ASSERT_GT(object.max, 0.0);
  EXPECT_NEAR(pc.sample(Phase::kU, 0.5).vdot[layout::kPhi], 0.5 * object.max, 1e-6 * object.max);
  EXPECT_NEAR(pc.sample(Phase::kU, -0.25).vdot[layout::kPhi], 0.25 * object.min,
              -1e-6 * object.min);
  EXPECT_NEAR(pc.sample(Phase::kU, 3.0).vdot[layout::kPhi], object.max, 1e-5 * object.max)
      << "fractions are clamped to [-1, 1]";
}

TEST(PhaseControlPreconditions, PhaseCNeedsTwoStickingContacts) {
  const RbsfModel one(test::makeCell(ShapeKind::kCircle, 1));
  PhaseControl pc1(one);
  const VecQ q1 = restingConfiguration(one, Pose{-0.03, 0.40, 0.0}, 0.0);
  ModelData d1(1);
  one.updateContacts(q1, d1);
  pc1.setState(q1, VecQ::Zero(5), d1);
  EXPECT_FALSE(pc1.solveC(0.0, 0.0).feasible);
  EXPECT_FALSE(pc1.rangeCBase().feasible);

  // Sliding contacts: not phase C, and sticking cannot hold whatever tau.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  PhaseControl pc(model);
  const VecQ q = restingConfiguration(model, Pose{0.10, 0.40, 0.0}, 0.0);
  ModelData d(3);
  model.updateContacts(q, d);
  std::mt19937 rng(71);
  const VecQ v = closedVelocity(d, rng);
  ASSERT_GT((d.T.transpose() * v).cwiseAbs().maxCoeff(), 1e-3);
  pc.setState(q, v, d);
  EXPECT_FALSE(pc.solveC(0.0, 0.0).feasible);
  const PhaseControlResult u = pc.solveU(0.0);
  ASSERT_TRUE(u.feasible);
  EXPECT_FALSE(u.stick_feasible);
}

INSTANTIATE_TEST_SUITE_P(Shapes, PhaseControlTest,
                         ::testing::Values(ShapeKind::kEllipse, ShapeKind::kCircle,
                                           ShapeKind::kSuperellipse));

}  // namespace
}  // namespace rbsf
