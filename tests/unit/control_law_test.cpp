// The control law's parts (feedback_schedule.h, control_law.h, sensor_model.h): the LQR
// gain stabilises an unstable balance that the open loop loses, the joint PD is the
// documented servo, the estimator follows a nominal plant from exact sensors and takes late
// part samples only within its history, the joint-only estimate finds a joint's rate, and
// the simulated sensors keep their rate, latency and stamps.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "law_support.h"
#include "rbsf/dynamics/control/sensor_model.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/plan_reference.h"

namespace rbsf {
namespace {

TEST(FeedbackSchedule, TheLqrGainHoldsABalanceTheOpenLoopLoses) {
  // The part on two frictionless tips at rest: the linearised step map alone has an
  // eigenvalue outside the unit circle (the inverted pendulum); closed by the gain, a
  // perturbation on the contacts' manifold decays.
  const RbsfModel model(test::twoTipsCell());
  const VecQ q0 = test::twoTipsConfiguration(model, 0.0);
  const plan::Plan plan = test::restPlan(model, q0, 1.0);
  const FeedbackSchedule schedule(model, plan::makeReference(plan), Sensing{}, SimulatorSettings{});
  ASSERT_TRUE(schedule.partFeedback());
  const int k = schedule.knotAt(0.5);
  const Eigen::MatrixXd& Ad = schedule.Ad(k);
  const double open = Ad.eigenvalues().cwiseAbs().maxCoeff();
  EXPECT_GT(open, 1.0 + 1e-4) << "the balance should be unstable open loop";
  // A tilted balance on the same tips (fingers re-placed), at rest.
  const VecQ q1 = restingConfiguration(model, Pose{0.002, 0.5, M_PI / 2 + 0.01}, 0.0);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(2 * model.configDim());
  e.head(model.configDim()) = q1 - q0;
  const Eigen::MatrixXd closed = Ad - schedule.Bd(k) * schedule.gain(k);
  Eigen::VectorXd x = e, y = e;
  for (int j = 0; j < 2000; ++j) {
    x = closed * x;
    y = Ad * y;
  }
  EXPECT_LT(x.head(3).norm(), 0.05 * e.head(3).norm()) << "2 s closed loop";
  EXPECT_GT(y.head(3).norm(), 10.0 * e.head(3).norm()) << "2 s open loop";
}

TEST(FeedbackSchedule, WithoutPartSensingTheGainIsTheJointServo) {
  const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0);
  Sensing blind;
  blind.part_pose.present = false;
  FeedbackSettings fs;
  const FeedbackSchedule schedule(model, plan::makeReference(test::holdPlan(model, q0, 0.5)), blind,
                                  SimulatorSettings{}, fs);
  EXPECT_FALSE(schedule.partFeedback());
  const Eigen::MatrixXd& K = schedule.gain(0);
  const int n = model.configDim();
  const Cell& c = model.cell();
  const double w = fs.servo.natural_frequency, z = fs.servo.damping_ratio;
  for (int j = 0; j < model.controlDim(); ++j) {
    const int col = layout::inputToConfig(j);
    const double inertia = j == 0 ? [&] {
      MatQQ M;
      model.massMatrix(q0, M);
      return M(3, 3) + c.object.inertia + c.object.mass * (q0[0] * q0[0] + q0[1] * q0[1]);
    }()
                                  : c.fingers[j - 1].mass + c.object.mass / 3;
    EXPECT_NEAR(K(j, col), inertia * w * w, 1e-9 * inertia * w * w);
    EXPECT_NEAR(K(j, n + col), inertia * 2 * z * w, 1e-9 * inertia * w);
    EXPECT_EQ(K.row(j).head(3).norm(), 0.0) << "no term on the part";
  }
}

TEST(ControlLaw, TheEstimateFollowsANominalPlantFromExactSensors) {
  // The part held at rest on the default cell, the plant the nominal simulator, sensors
  // exact: the estimate stays on the plant.
  const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0);
  const plan::Plan plan = test::holdPlan(model, q0, 0.5);
  const FeedbackSchedule schedule(model, plan::makeReference(plan), Sensing{}, SimulatorSettings{});
  ControlLaw law(schedule);
  SensorModel sensors(Sensing{}, 1e-3, 1, false);
  const Simulator plant(model);
  SimulatorWorkspace ws(3);
  SimState state(q0, VecQ::Zero(7));
  VecU joints, tau;
  VecQ q, v;
  double worst = 0.0;
  for (long n = 0; n < 800; ++n) {
    sensors.joints(state.q, joints);
    sensors.partPose(n, state.q, [&](double stamp, const Pose& p) { law.addPartPose(stamp, p); });
    law.compute(n * 1e-3, joints, tau);
    law.estimate(q, v);
    worst = std::max(worst, (q - state.q).cwiseAbs().maxCoeff());
    plant.step(state, tau, ws);
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT((state.q - q0).head(3).cwiseAbs().maxCoeff(), 1e-4) << "the part is held";
  EXPECT_EQ(law.droppedSamples(), 0u);
}

TEST(ControlLaw, APartSampleOlderThanItsHistoryIsDropped) {
  const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0);
  const FeedbackSchedule schedule(model, plan::makeReference(test::holdPlan(model, q0, 0.5)),
                                  Sensing{}, SimulatorSettings{});
  ControlLaw law(schedule);
  VecU joints = q0.segment(3, 4), tau;
  for (long n = 0; n < 100; ++n) law.compute(n * 1e-3, joints, tau);
  const Pose pose{q0[0], q0[1], q0[2]};
  law.addPartPose(0.099 - 0.01, pose);  // the default latency: kept
  law.compute(0.1, joints, tau);
  EXPECT_EQ(law.droppedSamples(), 0u);
  law.addPartPose(0.1 - 0.05, pose);  // 50 ms: beyond latency + two sample periods
  law.compute(0.101, joints, tau);
  EXPECT_EQ(law.droppedSamples(), 1u);
  law.addPartPose(std::nan(""), pose);
  EXPECT_EQ(law.droppedSamples(), 2u);
}

TEST(ControlLaw, TheJointServosEstimateFindsAJointsRate) {
  // A cell that does not see its part: the base measured turning at 0.2 rad/s off a plan
  // at rest; the estimate's rate converges on it within 0.1 s.
  const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0);
  Sensing blind;
  blind.part_pose.present = false;
  const FeedbackSchedule schedule(model, plan::makeReference(test::holdPlan(model, q0, 0.5)), blind,
                                  SimulatorSettings{});
  ControlLaw law(schedule);
  VecU joints = q0.segment(3, 4), tau;
  VecQ q, v;
  for (long n = 0; n <= 100; ++n) {
    joints[0] = q0[3] + 0.2 * n * 1e-3;
    law.compute(n * 1e-3, joints, tau);
  }
  law.estimate(q, v);
  EXPECT_NEAR(v[layout::kTheta], 0.2, 0.002);
  EXPECT_NEAR(q[layout::kTheta], q0[3] + 0.02, 1e-5);
  EXPECT_LT(tau[0], schedule.model().cell().base.torque_limit);
}

TEST(ControlLaw, NoiseFreeEncodersGiveAJointEstimateThatSettles) {
  // Exact encoders: the alpha-beta filter's limit (alpha 1, beta 2) would ring forever
  // after a step, its rate swinging by 2 x step / h; the capped filter settles.
  const RbsfModel model(test::makeCell(test::ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0);
  Sensing exact;
  exact.part_pose.present = false;
  exact.joints.angle_noise = exact.joints.stroke_noise = 0.0;
  const FeedbackSchedule schedule(model, plan::makeReference(test::holdPlan(model, q0, 0.5)), exact,
                                  SimulatorSettings{});
  ControlLaw law(schedule);
  VecU joints = q0.segment(3, 4), tau;
  VecQ q, v;
  double late_swing = 0.0;
  for (long n = 0; n <= 400; ++n) {
    if (n == 50) joints[1] += 1e-4;  // stroke 1 steps up 0.1 mm and stays
    law.compute(n * 1e-3, joints, tau);
    law.estimate(q, v);
    if (n > 300) late_swing = std::max(late_swing, std::abs(v[layout::stroke(0)]));
  }
  EXPECT_LT(late_swing, 1e-5);
  EXPECT_NEAR(q[layout::stroke(0)], joints[1], 1e-7);
}

TEST(SensorModel, PartSamplesKeepTheirRateLatencyAndStamps) {
  Sensing s;
  s.part_pose.rate = 50.0;
  s.part_pose.latency = 0.015;
  SensorModel exact(s, 1e-3, 1, false, Vec2(0.001, 0.0));
  VecQ q = VecQ::Zero(7);
  q[0] = 0.1, q[1] = 0.4, q[2] = M_PI / 2;
  std::vector<std::pair<long, double>> delivered;  // step, stamp
  for (long n = 0; n < 100; ++n)
    exact.partPose(n, q, [&](double stamp, const Pose& p) {
      delivered.emplace_back(n, stamp);
      EXPECT_NEAR(p.x, 0.1, 1e-12);  // the COM offset (1 mm along the part's x) removed
      EXPECT_NEAR(p.y, 0.4 - 0.001, 1e-12);
    });
  ASSERT_EQ(delivered.size(), 5u);  // taken at 0, 20, 40, 60, 80 ms
  for (std::size_t k = 0; k < delivered.size(); ++k) {
    EXPECT_NEAR(delivered[k].second, 0.02 * k, 1e-12);
    EXPECT_EQ(delivered[k].first, static_cast<long>(20 * k + 15));
  }
  // Noisy joints scatter with the sensing's standard deviation.
  SensorModel noisy(s, 1e-3, 3);
  VecU j;
  double sum2 = 0.0;
  for (int n = 0; n < 4000; ++n) {
    noisy.joints(q, j);
    sum2 += j[0] * j[0];
  }
  EXPECT_NEAR(std::sqrt(sum2 / 4000), s.joints.angle_noise, 0.1 * s.joints.angle_noise);
}

}  // namespace
}  // namespace rbsf
