// The control sampler's inverse dynamics by phase (planner/phase_targets.h): each tau it
// returns is run through the forward dynamics of its phase, which must do what was targeted:
// phase C through solvePhaseC against the rigid motion computed from the kinematics alone,
// phase U through the simulator's LCP (forwardDynamicsU).
#include <gtest/gtest.h>

#include <random>

#include <Eigen/SVD>

#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/stick_dynamics.h"
#include "rbsf/planner/kinodynamic/phase_targets.h"
#include "test_support.h"

namespace rbsf {
namespace {

using test::ShapeKind;

constexpr double kTouch = 1e-3;  // the planner's default touch distance [m]

// A random velocity in the null space of the rows of C (every such row stays zero).
VecQ nullSpaceVelocity(const Eigen::MatrixXd& C, std::mt19937& rng, double scale) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const Eigen::MatrixXd null = svd.matrixV().rightCols(C.cols() - svd.rank());
  return null * test::randomVector(static_cast<int>(null.cols()), rng, scale);
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

// True when no input is at the cell's limit (a clipped tau no longer carries the target).
bool insideLimits(const RbsfModel& model, const VecU& tau) {
  if (std::abs(tau[layout::kTauTheta]) >= model.cell().base.torque_limit) return false;
  for (int i = 0; i < model.numFingers(); ++i)
    if (std::abs(tau[layout::fingerForce(i)]) >= model.cell().fingers[i].force_limit) return false;
  return true;
}

class PhaseTargetsTest : public ::testing::TestWithParam<ShapeKind> {};

TEST_P(PhaseTargetsTest, StickTauMakesTheStickingDynamicsDoTheRigidMotion) {
  for (int m : {3, 4}) {
    const RbsfModel model(test::makeCell(GetParam(), m));
    planner::PhaseTargeting targeting(model, kTouch);
    std::mt19937 rng(31 + m);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 20; ++trial) {
      const VecQ q = test::randomContactState(model, rng);
      ModelData d(m);
      model.updateContacts(q, d);
      Eigen::MatrixXd C(2 * m, model.configDim());
      C << d.G1.transpose(), d.T.transpose();
      const VecQ v = nullSpaceVelocity(C, rng, 0.5);  // every contact sticking
      const planner::StickTarget target{2.0 * u(rng), 0.5 * u(rng)};
      VecU tau;
      ASSERT_TRUE(targeting.stickTau(q, v, target, tau));
      if (!insideLimits(model, tau)) continue;
      ++checked;
      const VecQ rigid = rigidAcceleration(model, q, v, target.base_accel, target.stroke_accel);
      const StickSolution s = solvePhaseC(model, q, v, tau, d);
      EXPECT_LT((s.vdot - rigid).norm(), 1e-7 * (1.0 + rigid.norm()))
          << "m = " << m << ", trial " << trial;
    }
    EXPECT_GE(checked, 15) << "m = " << m;
  }
}

TEST_P(PhaseTargetsTest, SlideTauMakesTheLcpDoTheTargetedSlide) {
  for (int m : {3, 4}) {
    const RbsfModel model(test::makeCell(GetParam(), m));  // frictionless: mu_k = 0
    planner::PhaseTargeting targeting(model, kTouch);
    std::mt19937 rng(41 + m);
    std::uniform_real_distribution<double> force(20.0, 150.0), u(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 20; ++trial) {
      const VecQ q = test::randomContactState(model, rng);
      ModelData d(m);
      model.updateContacts(q, d);
      const VecQ v = nullSpaceVelocity(d.G1.transpose(), rng, 0.5);  // closed, sliding
      // An achievable slide: the object's acceleration under random pressing forces.
      const Cell& cell = model.cell();
      Eigen::Vector3d load(0.0, -cell.object.mass * cell.gravity, 0.0);
      VecC drawn(m);
      for (int i = 0; i < m; ++i) {
        drawn[i] = force(rng);
        load += drawn[i] * d.G1.col(i).head<3>();
      }
      planner::SlideTarget target;
      target.accel_x = load[0] / cell.object.mass;
      target.accel_y = load[1] / cell.object.mass;
      target.omega_dot = load[2] / cell.object.inertia;
      target.base_accel = 2.0 * u(rng);
      VecU tau;
      ASSERT_TRUE(targeting.slideTau(q, v, target, tau));
      if (!insideLimits(model, tau)) continue;
      ++checked;
      ModelData e(m);
      forwardDynamicsU(model, q, v, tau, e);
      const double scale = 1.0 + e.vdot.norm();
      EXPECT_NEAR(e.vdot[layout::kX], target.accel_x, 1e-7 * scale);
      EXPECT_NEAR(e.vdot[layout::kY], target.accel_y, 1e-7 * scale);
      EXPECT_NEAR(e.vdot[layout::kPhi], target.omega_dot, 1e-7 * scale);
      EXPECT_NEAR(e.vdot[layout::kTheta], target.base_accel, 1e-7 * scale);
      for (int i = 0; i < m; ++i) {
        EXPECT_LT(std::abs(e.delta_n[i]), 1e-7 * scale) << "contact " << i << " stays closed";
        // Three contacts on a part whose normals do not meet in one point: the forces are
        // unique, so they are the drawn ones. (Four contacts, or a circle's normals through
        // its centre: NNLS picks one of many solutions, some forces zero.)
        if (m == 3 && GetParam() != ShapeKind::kCircle) {
          EXPECT_NEAR(e.fn[i], drawn[i], 1e-6 * drawn.norm()) << "contact " << i;
        }
      }
    }
    EXPECT_GE(checked, 15) << "m = " << m;
  }
}

TEST(PhaseTargets, PhasesNeedTheirContacts) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  planner::PhaseTargeting targeting(model, kTouch);
  std::mt19937 rng(5);
  VecQ q = test::randomContactState(model, rng);
  const VecQ v = VecQ::Zero(model.configDim());
  VecU tau;
  // Two fingers lowered 1 cm off the part: one touches, too few to stick, enough to slide.
  q[layout::stroke(0)] -= 0.01;
  q[layout::stroke(1)] -= 0.01;
  EXPECT_FALSE(targeting.stickTau(q, v, planner::StickTarget{}, tau));
  EXPECT_TRUE(targeting.slideTau(q, v, planner::SlideTarget{}, tau));
  q[layout::stroke(2)] -= 0.01;  // none touches
  EXPECT_FALSE(targeting.slideTau(q, v, planner::SlideTarget{}, tau));
}

TEST(PhaseTargets, FreeFingersGetTheirStrokeAccelerationInPhaseU) {
  // Finger 1 lowered off the part: its row of M dv/dt + Q = B tau + G1 F_n has no contact
  // force, so the tau it gets must give it the free stroke acceleration asked for, whatever
  // the part does.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 4));
  planner::PhaseTargeting targeting(model, kTouch);
  std::mt19937 rng(9);
  VecQ q = test::randomContactState(model, rng);
  q[layout::stroke(1)] -= 0.01;
  const VecQ v = VecQ::Zero(model.configDim());
  planner::SlideTarget target;
  target.free_stroke_accel = 0.7;
  VecU tau;
  ASSERT_TRUE(targeting.slideTau(q, v, target, tau));
  ASSERT_TRUE(insideLimits(model, tau));
  ModelData d(4);
  model.updateContacts(q, d);
  ASSERT_GT(d.contacts[1].gap, kTouch);
  // The stroke rows of the mass matrix couple a finger to the base rotation only.
  MatQQ M;
  VecQ Q, u_gen;
  model.massMatrix(q, M);
  model.bias(q, v, Q);
  model.generalizedInput(tau, u_gen);
  const int k = layout::stroke(1);
  const double coupling = M(k, layout::kTheta) * target.base_accel;
  EXPECT_NEAR((u_gen[k] - Q[k] - coupling) / M(k, k), target.free_stroke_accel, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Shapes, PhaseTargetsTest,
                         ::testing::Values(ShapeKind::kEllipse, ShapeKind::kCircle,
                                           ShapeKind::kSuperellipse));

}  // namespace
}  // namespace rbsf
