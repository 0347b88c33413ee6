// Hot paths allocate nothing: mallocs are counted around each one after warm-up.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <random>
#include <vector>

#include "../unit/test_support.h"
#include "malloc_counter.h"
#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/core/forward_dynamics.h"
#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/small_qp.h"
#include "rbsf/dynamics/core/small_solvers.h"

namespace rbsf {
namespace {

class NoAllocation : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::mallocCountingAvailable()) GTEST_SKIP() << "malloc not countable in this build";
  }
};

TEST_F(NoAllocation, CounterSeesMalloc) {
  test::MallocCounter counter;
  void* volatile probe = std::malloc(64);
  std::free(probe);
  EXPECT_EQ(counter.count(), 1);
}

TEST_F(NoAllocation, CounterSeesCallocAndRealloc) {
  test::MallocCounter counter;
  void* volatile zeroed = std::calloc(8, 8);
  void* volatile grown = std::realloc(zeroed, 4096);
  std::free(grown);
  EXPECT_EQ(counter.count(), 2);
}

TEST_F(NoAllocation, LcpSolve) {
  std::mt19937 rng(5);
  std::vector<MatCC> As;
  std::vector<VecC> ps;
  for (int n = 1; n <= kMaxFingers; ++n) {
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
    As.push_back(MatCC(B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n)));
    ps.push_back(VecC(Eigen::VectorXd::Random(n)));  // mixed signs: pivoting happens
  }
  VecC z, w;
  int pivots = 0;
  test::MallocCounter counter;
  for (size_t i = 0; i < As.size(); ++i) pivots += solveLcp(As[i], ps[i], z, w).pivots;
  EXPECT_EQ(counter.count(), 0);
  EXPECT_GT(pivots, 0);
}

TEST_F(NoAllocation, SmallQpSolve) {
  // Problems of every size class up to capacity, feasible (rows added and dropped) and
  // infeasible, equality rows included; constructed before counting.
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<SmallQp> problems;
  const std::array<std::array<int, 3>, 7> sizes = {
      {{1, 0, 2}, {6, 0, 20}, {6, 1, 20}, {9, 0, 15}, {12, 3, 48}, {16, 4, 96}, {16, 16, 96}}};
  for (const auto& [n, me, mi] : sizes) {
    for (const bool feasible : {true, false}) {
      SmallQp& qp = problems.emplace_back(n, me, mi);
      Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); });
      qp.H = B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
      QpVecN x_f = QpVecN::NullaryExpr(n, [&] { return u(rng); });
      qp.g = 5.0 * QpVecN::NullaryExpr(n, [&] { return u(rng); });
      qp.A_eq = QpMatEN::NullaryExpr(me, n, [&] { return u(rng); });
      qp.b_eq = qp.A_eq * x_f;
      qp.A = QpMatIN::NullaryExpr(mi, n, [&] { return u(rng); });
      qp.b = qp.A * x_f - QpVecI::NullaryExpr(mi, [&] { return 0.5 + 0.5 * u(rng); });
      if (!feasible) {  // a^T x >= 1 and a^T x <= 0
        qp.A.row(mi - 1) = -qp.A.row(0);
        qp.b[0] = 1.0;
        qp.b[mi - 1] = 0.0;
      }
    }
  }
  int steps = 0, optimal = 0, infeasible = 0;
  test::MallocCounter counter;
  for (SmallQp& qp : problems) {
    const QpStatus status = qp.solve();
    steps += qp.iterations;
    optimal += status == QpStatus::kOptimal;
    infeasible += status == QpStatus::kInfeasible;
  }
  EXPECT_EQ(counter.count(), 0);
  EXPECT_EQ(optimal, 7);
  EXPECT_EQ(infeasible, 7);
  EXPECT_GT(steps, 50);
}

TEST_F(NoAllocation, ForwardDynamicsEvaluation) {
  for (int m : {2, 3, 6, 8}) {
    const RbsfModel model(test::makeCell(test::ShapeKind::kSuperellipse, m));
    std::mt19937 rng(m);
    const VecQ q = test::randomContactState(model, rng);
    const VecQ v = test::randomVector(model.configDim(), rng, 0.3);
    const VecU tau = test::randomVector(model.controlDim(), rng, 100.0);
    ModelData data(m);
    forwardDynamicsU(model, q, v, tau, data);  // warm-up: global closest-point search
    test::MallocCounter counter;
    for (int k = 0; k < 100; ++k) forwardDynamicsU(model, q, v, tau, data);
    EXPECT_EQ(counter.count(), 0) << "m = " << m;
  }
}

TEST_F(NoAllocation, SimulatorStep) {
  // Held, then tilted until the part slides off: sticking, sliding, separating and limit
  // rows all pass through the counted steps, on both solver paths.
  for (int m : {3, 6}) {
    for (int iterations : {8, 0}) {
      const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, m));
      const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
      ModelData d(m);
      model.updateContacts(q0, d);
      const HoldingSolution hold = holdingTorques(model, q0, d);
      ASSERT_TRUE(hold.feasible);
      SimulatorSettings settings;
      settings.max_mode_iterations = iterations;  // 0: Lemke on every step
      const Simulator sim(model, settings);
      SimulatorWorkspace ws(m);
      SimState s(q0, VecQ::Zero(m + 4));
      StepReport report;
      VecU tau = hold.tau;
      sim.step(s, tau, ws, &report);  // warm-up: global closest-point search
      int phases[4] = {0, 0, 0, 0};
      test::MallocCounter counter;
      for (int k = 0; k < 3000; ++k) {
        tau = hold.tau;
        tau[layout::kTauTheta] += 2e4 * (0.5 * std::max(0.0, s.t - 0.5) - s.q[layout::kTheta]) -
                                  2e3 * s.v[layout::kTheta];
        sim.step(s, tau, ws, &report);
        ++phases[static_cast<int>(report.phase)];
      }
      EXPECT_EQ(counter.count(), 0) << "m = " << m << ", iterations = " << iterations;
      EXPECT_GT(phases[static_cast<int>(Phase::kC)], 0) << m;
      EXPECT_GT(phases[static_cast<int>(Phase::kU)] + phases[static_cast<int>(Phase::kUnsupported)],
                0)
          << m;
    }
  }
}

TEST_F(NoAllocation, ReferenceSamplingAndTheControlLaw) {
  const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  ReferenceTrajectory ref;
  VecQ v = VecQ::Zero(7);
  for (int k = 0; k <= 100; ++k) {
    v[layout::kTheta] = 0.01 * k;
    ref.addKnot(0.01 * k, q0, v);
  }
  const VecU tau0 = VecU::Constant(4, 10.0), tau1 = VecU::Constant(4, 20.0);
  // Every role in turn: sticking, sliding both ways (pulled loose, then with a slip floor),
  // lifted (a barrier), free, and none stated.
  const char* roles[] = {"SSS", "LS+", "LS+", "L-S", "SFS", "+S-", "LSS", "", "S+S", "SSL"};
  for (int j = 0; j < 10; ++j)
    ref.addInputPiece(0.1 * j, 0.1, tau0, j % 2 ? tau1 : VecU(), Phase::kC,
                      *roles[j] ? parseRoles(roles[j], 3, "roles") : ContactRoles{});
  for (const bool part : {true, false}) {
    Sensing sensing;
    sensing.part_pose.present = part;
    FeedbackSettings fs;
    fs.timing.settle_time = 0.2;
    const FeedbackSchedule schedule(model, ref, sensing, SimulatorSettings{}, fs);
    ControlLaw law(schedule);
    ReferenceSample sample;
    VecU tau, joints(4);
    ref.sample(0.0, sample);
    double sum = 0.0;
    test::MallocCounter counter;
    for (int k = 0; k < 1300; ++k) {  // beyond the plan: the hold
      const double t = 1e-3 * k;
      schedule.reference(t, sample);
      for (int j = 0; j < 4; ++j) joints[j] = sample.q[layout::inputToConfig(j)] + 1e-5 * j;
      if (k % 10 == 0 && k >= 10)
        law.addPartPose(t - 0.01, Pose{sample.q[layout::kX], sample.q[layout::kY], 0.001});
      law.compute(t, joints, tau);
      sum += tau[0];
    }
    EXPECT_EQ(counter.count(), 0) << (part ? "part feedback" : "joint PD");
    EXPECT_TRUE(std::isfinite(sum));
  }
}

}  // namespace
}  // namespace rbsf
