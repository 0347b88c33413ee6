// The hybrid simulator through stick, slip, separation and renewed contact: holding at
// rest, turning with the base in phase C, energy in frictionless sliding, an inelastic
// touch, the hard limits, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "sim_test_support.h"

namespace rbsf {
namespace {

using layout::kPhi;
using layout::kTauTheta;
using layout::kTheta;
using layout::kX;
using layout::kY;
using test::ShapeKind;

TEST(Simulator, HeldPartStaysPutForSixtySeconds) {
  // The part rests on three fingers; each finger gets exactly its holding force from the
  // analysis. The base angle is an inverted pendulum (part and carriages sit above the base
  // axis: with a constant tau_theta any perturbation grows like exp(t / 0.3 s), which is
  // physics, not numerics), so the base gets a PD on its angle on top of the holding
  // torque. Its output is zero at the equilibrium: the part stays put only if the
  // simulator's contact forces balance what the analysis says, to rounding.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  const HoldingSolution hold = test::holdingAt(model, q0);
  ASSERT_TRUE(hold.feasible);
  const Simulator sim(model);
  ASSERT_EQ(sim.settings().time_step, 1e-3);
  SimulatorWorkspace ws(3);
  SimState s(q0, VecQ::Zero(7));
  StepReport rep;
  double max_gap = 0.0, max_move = 0.0, max_turn = 0.0, max_stroke = 0.0;
  int not_c = 0;
  for (int k = 0; k < 60000; ++k) {
    VecU tau = hold.tau;
    tau[kTauTheta] += -2e3 * (s.q[kTheta] - q0[kTheta]) - 300.0 * s.v[kTheta];
    sim.step(s, tau, ws, &rep);
    not_c += rep.phase != Phase::kC || rep.sticking != 3;
    for (int i = 0; i < 3; ++i) max_gap = std::max(max_gap, std::abs(rep.contacts[i].gap));
    max_move = std::max(max_move, std::hypot(s.q[kX] - q0[kX], s.q[kY] - q0[kY]));
    max_turn = std::max({max_turn, std::abs(s.q[kPhi] - q0[kPhi]), std::abs(s.q[kTheta])});
    max_stroke = std::max(max_stroke, (s.q.tail(3) - q0.tail(3)).cwiseAbs().maxCoeff());
  }
  RecordProperty("max_gap_m", test::figure(max_gap));
  RecordProperty("max_displacement_m", test::figure(max_move));
  RecordProperty("max_rotation_rad", test::figure(max_turn));
  EXPECT_NEAR(s.t, 60.0, 1e-9);
  EXPECT_EQ(not_c, 0);
  EXPECT_LT(max_gap, 1e-6);
  EXPECT_LT(max_move, 1e-6);
  EXPECT_LT(max_turn, 1e-6);
  EXPECT_LT(max_stroke, 1e-6);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(rep.contacts[i].f_n, hold.fn[i], 1e-6 * hold.fn.norm()) << i;
    EXPECT_NEAR(rep.contacts[i].f_t, hold.ft[i], 1e-6 * hold.fn.norm()) << i;
  }
}

TEST(Simulator, ReportedNormalForcesNeverPull) {
  // "Contacts never pull" is checked on reports (the replay's min f_n >= 0), so a closed
  // contact that carries no load must read 0, not the solvers' rounding: the default part
  // resting on unpowered fingers (tau = 0) read -3.3e-35 N at step 5. Then every report of
  // a random drive, on every shape, is >= 0, and 0 when separated.
  {
    const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
    const Simulator sim(model);
    SimulatorWorkspace ws(3);
    StepReport rep;
    SimState s(restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0), VecQ::Zero(7));
    for (int k = 0; k < 50; ++k) {
      sim.step(s, VecU::Zero(4), ws, &rep);
      for (int i = 0; i < 3; ++i) ASSERT_GE(rep.contacts[i].f_n, 0.0) << k << " " << i;
    }
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int closed = 0;
  for (ShapeKind kind : {ShapeKind::kEllipse, ShapeKind::kCircle, ShapeKind::kSuperellipse}) {
    const RbsfModel model(test::makeCell(kind, 3));
    const Simulator sim(model);
    SimulatorWorkspace ws(3);
    StepReport rep;
    for (int trial = 0; trial < 20; ++trial) {
      const VecQ q0 = test::randomContactState(model, rng);
      const HoldingSolution hold = test::holdingAt(model, q0);
      if (!hold.feasible) continue;
      SimState s(q0, VecQ::Zero(7));
      VecU tau = hold.tau;
      for (int k = 0; k < 300; ++k) {
        if (k % 20 == 0)
          for (int j = 0; j < tau.size(); ++j) tau[j] = hold.tau[j] * (1.0 + 0.3 * u(rng));
        tau[kTauTheta] += -2e3 * s.q[kTheta] - 300.0 * s.v[kTheta];
        sim.step(s, tau, ws, &rep);
        for (int i = 0; i < 3; ++i) {
          const ContactStepReport& c = rep.contacts[i];
          if (c.mode == ContactMode::kSeparated) {
            EXPECT_EQ(c.f_n, 0.0);
          } else {
            ++closed;
            ASSERT_GE(c.f_n, 0.0) << "trial " << trial << " step " << k << " contact " << i;
          }
        }
      }
    }
  }
  EXPECT_GT(closed, 10000);
}

TEST(Simulator, PartTurnsWithTheBaseThroughoutPhaseC) {
  // Paper 2.2: with two or more sticking contacts the part moves rigidly with the base.
  // The base swings to 0.3 rad and back; the fingers get the holding tau of the current base
  // angle (from the analysis, tabulated) plus a PD on their strokes. Every step must be
  // phase C with all three contacts sticking, and the part's pose in the base frame must
  // not change.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  const double amplitude = 0.3, period = 6.0, w = 2.0 * M_PI / period;
  const int table_size = 31;
  std::vector<VecU> table;
  for (int j = 0; j < table_size; ++j) {
    const HoldingSolution hold =
        test::holdingAt(model, test::turnedWithBase(q0, amplitude * j / (table_size - 1)));
    ASSERT_TRUE(hold.feasible) << j;
    table.emplace_back(hold.tau);
  }
  auto feedforward = [&](double theta) {
    const double x = std::clamp(theta / amplitude, 0.0, 1.0) * (table_size - 1);
    const int j = std::min(static_cast<int>(x), table_size - 2);
    return VecU((j + 1 - x) * table[j] + (x - j) * table[j + 1]);
  };
  const Simulator sim(model);
  SimulatorWorkspace ws(3);
  SimState s(q0, VecQ::Zero(7));
  StepReport rep;
  const test::Servo servo;
  const VecC strokes = test::strokesOf(q0);
  const Vec2 rel0 = Vec2(q0[kX], q0[kY]);
  double max_rel = 0.0, max_turn = 0.0, max_theta = 0.0;
  int not_c = 0;
  for (int k = 0; k < static_cast<int>(period * 1000); ++k) {
    const double ref = 0.5 * amplitude * (1.0 - std::cos(w * s.t));
    const double ref_dot = 0.5 * amplitude * w * std::sin(w * s.t);
    sim.step(s, servo(feedforward(s.q[kTheta]), s, ref, ref_dot, strokes), ws, &rep);
    not_c += rep.phase != Phase::kC || rep.sticking != 3;
    // Part in the base frame, less the common stroke (the one free motion of phase C
    // besides the base rotation).
    const double common = (s.q.tail(3) - q0.tail(3)).mean();
    const Vec2 rel = rotate(-s.q[kTheta], Vec2(s.q[kX], s.q[kY])) - Vec2(0.0, common);
    max_rel = std::max(max_rel, (rel - rel0).norm());
    max_turn = std::max(max_turn, std::abs(s.q[kPhi] - s.q[kTheta] - q0[kPhi]));
    max_theta = std::max(max_theta, s.q[kTheta]);
  }
  RecordProperty("max_pose_change_in_base_frame_m", test::figure(max_rel));
  EXPECT_GT(max_theta, 0.29);  // the base did turn
  EXPECT_EQ(not_c, 0);
  EXPECT_LT(max_turn, 1e-9);
  EXPECT_LT(max_rel, 1e-9);
}

TEST(Simulator, FrictionlessSlidingWithoutGravityConservesEnergy) {
  // No gravity, no friction, constant tau: the inputs are a constant generalised force u,
  // whose potential is -u.q, so E = 1/2 v^T M v - u.(q - q0) is conserved. tau is the
  // holding tau of a "gravity" of 0.01 m/s^2, which makes part and fingers accelerate
  // upwards together; the part starts moving down (it turns back after 5 s), sideways and
  // turning, with the base turning too, every contact sliding with its normal velocity 0.
  Cell cell = test::makeCell(ShapeKind::kEllipse, 3);
  cell.friction = {0.0, 0.0};
  Cell lift = cell;
  lift.gravity = 0.01;
  lift.friction.mu_static = 1.0;
  cell.gravity = 0.0;
  const RbsfModel model(cell), lift_model(lift);
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  const HoldingSolution hold = test::holdingAt(lift_model, q0);
  ASSERT_TRUE(hold.feasible);
  ModelData d(3);
  model.updateContacts(q0, d);
  VecQ v = VecQ::Zero(7);
  v[kX] = 0.01, v[kY] = -0.05, v[kPhi] = 0.05, v[kTheta] = 0.01;
  for (int i = 0; i < 3; ++i)
    v[layout::stroke(i)] = -d.G1.col(i).dot(v) / d.G1(layout::stroke(i), i);  // G1^T v = 0
  const VecU tau = hold.tau;
  VecQ u;
  model.generalizedInput(tau, u);
  const double e0 = model.kineticEnergy(q0, v);
  const Simulator sim(model);
  SimulatorWorkspace ws(3);
  SimState s(q0, v);
  StepReport rep;
  double max_drift = 0.0, max_slip = 0.0;
  int not_touching = 0;
  for (int k = 0; k < 10000; ++k) {
    sim.step(s, tau, ws, &rep);
    const double e = model.kineticEnergy(s.q, s.v) - u.dot(s.q - q0);
    max_drift = std::max(max_drift, std::abs(e - e0) / e0);
    not_touching += rep.touching != 3;
    for (int i = 0; i < 3; ++i) max_slip = std::max(max_slip, std::abs(rep.contacts[i].slip));
    ASSERT_EQ(rep.limit_force.norm(), 0.0) << "a hard limit would dissipate";
  }
  RecordProperty("energy_drift_percent", test::figure(100.0 * max_drift));
  EXPECT_EQ(not_touching, 0);
  EXPECT_GT(max_slip, 0.01);                       // it did slide
  EXPECT_GT(std::abs(s.q[kPhi] - q0[kPhi]), 0.1);  // and the part turned on the fingers
  EXPECT_LT(max_drift, 0.005);
}

TEST(Simulator, LoweredFingerSeparatesAndTouchesAgainWithoutGainingEnergy) {
  // All fingers servo their strokes around the holding tau; the middle finger's target drops
  // by 1 cm at t = 0.5 s, stays there, and rises back at 2 cm/s from t = 1.5 s. The outer
  // fingers keep the part (phase C). Energy bookkeeping per step: mechanical energy
  // E = KE + PE may change only by the work of tau over the step, u.(q+ - q); the touch must
  // dissipate (inelastic), and the finger must stay on the part afterwards (no rebound).
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  const HoldingSolution hold = test::holdingAt(model, q0);
  ASSERT_TRUE(hold.feasible);
  const Simulator sim(model);
  SimulatorWorkspace ws(3);
  SimState s(q0, VecQ::Zero(7));
  StepReport rep;
  test::Servo servo;
  servo.kd_stroke = 400.0;
  double max_gap = 0.0, max_gain = -1.0, touch_loss = 0.0, ke_before = -1.0, ke_after = -1.0;
  int separated_steps = 0, touch_step = -1, rebounds = 0;
  ContactMode last = ContactMode::kStick;
  for (int k = 0; k < 3500; ++k) {
    const double t = s.t;
    const double drop = t < 0.5 ? 0.0 : t < 1.5 ? 0.01 : std::max(0.0, 0.01 - 0.02 * (t - 1.5));
    VecC strokes = test::strokesOf(q0);
    strokes[1] -= drop;
    const VecU tau = servo(hold.tau, s, 0.0, 0.0, strokes);
    VecQ u;
    model.generalizedInput(tau, u);
    const VecQ q = s.q, v = s.v;
    const double e_before = model.kineticEnergy(q, v) + model.potentialEnergy(q);
    sim.step(s, tau, ws, &rep);
    const double gain =
        model.kineticEnergy(s.q, s.v) + model.potentialEnergy(s.q) - e_before - u.dot(s.q - q);
    max_gain = std::max(max_gain, gain);
    const ContactMode mode = rep.contacts[1].mode;
    if (mode == ContactMode::kSeparated) {
      ++separated_steps;
      max_gap = std::max(max_gap, rep.contacts[1].gap);
      if (touch_step >= 0) ++rebounds;
    } else if (last == ContactMode::kSeparated && touch_step < 0) {
      touch_step = k;
      touch_loss = gain;
      ke_before = model.kineticEnergy(q, v);
      ke_after = model.kineticEnergy(s.q, s.v);
    }
    last = mode;
  }
  EXPECT_GT(separated_steps, 1000);
  EXPECT_GT(max_gap, 2e-3);  // it really left the part
  ASSERT_GT(touch_step, 1500) << "the finger touched again while rising";
  EXPECT_EQ(rebounds, 0);
  EXPECT_LT(touch_loss, -1e-6) << "an inelastic touch dissipates";
  EXPECT_LE(ke_after, ke_before);
  EXPECT_LT(max_gain, 1e-9) << "no step creates energy";
  EXPECT_EQ(rep.touching, 3);
}

TEST(Simulator, StrokeEndsAndBaseRangeAreHardStops) {
  // The part is out of reach (it falls freely: phase unsupported). Finger 1 is pushed up,
  // finger 2 pulled down, finger 3 left to fall, the base turned: each must stop at its
  // limit and stay there.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const Cell& cell = model.cell();
  VecQ q = VecQ::Zero(7);
  q << 0.1, 2.0, 0.0, 0.0, 0.3, 0.3, 0.3;
  const Simulator sim(model);
  SimulatorWorkspace ws(3);
  SimState s(q, VecQ::Zero(7));
  StepReport rep;
  VecU tau = VecU::Zero(4);
  tau[kTauTheta] = 100.0;
  tau[layout::fingerForce(0)] = 200.0;
  tau[layout::fingerForce(1)] = -200.0;
  double overshoot = 0.0;
  for (int k = 0; k < 400; ++k) {  // 0.4 s: the part is still far above the fingers
    sim.step(s, tau, ws, &rep);
    EXPECT_EQ(rep.phase, Phase::kUnsupported);
    overshoot = std::max({overshoot, s.q[layout::stroke(0)] - cell.fingers[0].stroke_max,
                          cell.fingers[1].stroke_min - s.q[layout::stroke(1)],
                          s.q[kTheta] - cell.base.theta_max});
  }
  EXPECT_LT(overshoot, 1e-9);
  EXPECT_NEAR(s.q[layout::stroke(0)], cell.fingers[0].stroke_max, 1e-9);
  EXPECT_NEAR(s.q[layout::stroke(1)], cell.fingers[1].stroke_min, 1e-9);
  EXPECT_NEAR(s.q[kTheta], cell.base.theta_max, 1e-9);
  // Inelastic: resting on the stops, no velocity into or out of them.
  EXPECT_LT(std::abs(s.v[layout::stroke(0)]), 1e-9);
  EXPECT_LT(std::abs(s.v[layout::stroke(1)]), 1e-9);
  EXPECT_LT(std::abs(s.v[kTheta]), 1e-9);
  // The stops push back: on finger 1 down, finger 2 up, the base clockwise.
  EXPECT_LT(rep.limit_force[layout::stroke(0)], 0.0);
  EXPECT_GT(rep.limit_force[layout::stroke(1)], 0.0);
  EXPECT_LT(rep.limit_force[kTheta], 0.0);
  // The part fell freely all along: y = y0 - g t^2 / 2 to O(h).
  EXPECT_NEAR(s.q[kY], 2.0 - 0.5 * cell.gravity * s.t * s.t, cell.gravity * s.t * 1e-3);
}

TEST(Simulator, APartOnlyDriftCorrectionClosesTheGapsWithTheJointsHeld) {
  // The held part pressed 0.1 mm into its three tips: the velocity solve leaves the
  // penetration (closed rows carry no gap term), the drift correction removes it. The
  // plant's correction moves every coordinate (the light carriages most); the estimator's
  // moves the part alone, so its joints end the step where an uncorrected step puts them.
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  const VecQ q0 = restingConfiguration(model, Pose{0.1, 0.40, 0.0}, 0.0);
  const HoldingSolution hold = test::holdingAt(model, q0);
  ASSERT_TRUE(hold.feasible);
  VecQ pressed = q0;
  pressed[kY] -= 1e-4;
  auto stepWith = [&](bool correct, bool part_only) {
    SimulatorSettings settings;
    settings.drift_correction = correct;
    settings.drift_moves_part_only = part_only;
    const Simulator sim(model, settings);
    SimulatorWorkspace ws(3);
    SimState s(q0, VecQ::Zero(7));
    sim.step(s, hold.tau, ws);  // the contacts stick and are anchored at rest
    s.q = pressed;
    s.v.setZero();
    StepReport rep;
    sim.step(s, hold.tau, ws, &rep);
    ModelData d(3);
    model.updateContacts(s.q, d);
    double worst_gap = 0.0;
    for (int i = 0; i < 3; ++i) worst_gap = std::max(worst_gap, std::abs(d.contacts[i].gap));
    return std::make_pair(s.q, worst_gap);
  };
  const auto [q_none, gap_none] = stepWith(false, false);
  const auto [q_all, gap_all] = stepWith(true, false);
  const auto [q_part, gap_part] = stepWith(true, true);
  EXPECT_GT(gap_none, 5e-5) << "the velocity solve alone leaves the penetration";
  EXPECT_LT(gap_all, 1e-7);
  EXPECT_LT(gap_part, 1e-7);
  const int n = model.configDim();
  const auto joints = [&](const VecQ& q) -> VecQ { return q.segment(kTheta, n - kTheta); };
  EXPECT_TRUE(test::sameBits(joints(q_part), joints(q_none)));
  EXPECT_GT((joints(q_all) - joints(q_none)).cwiseAbs().maxCoeff(), 1e-6)
      << "the plant's correction moves the carriages";
  EXPECT_GT(q_part[kY] - q_none[kY], 5e-5) << "the part is lifted out of its tips";
}

TEST(Simulator, DeterministicAndResumableBitForBit) {
  // The tilt-and-slide of a held part (stick, slip, separation, Lemke fallbacks if any):
  // two runs give the same bits, and so does a run resumed from a saved state with a new
  // workspace.
  const RbsfModel model(test::makeCell(ShapeKind::kSuperellipse, 4));
  const VecQ q0 = restingConfiguration(model, Pose{-0.05, 0.40, 0.1}, 0.0);
  const HoldingSolution hold = test::holdingAt(model, q0);
  ASSERT_TRUE(hold.feasible);
  const Simulator sim(model);
  const test::Servo servo;
  const VecC strokes = test::strokesOf(q0);
  auto run = [&](SimState& s, SimulatorWorkspace& ws, int steps) {
    StepReport rep;
    for (int k = 0; k < steps; ++k)
      sim.step(s, servo(hold.tau, s, 0.5 * s.t, 0.5, strokes), ws, &rep);
  };
  SimulatorWorkspace ws1(4), ws2(4), ws3(4);
  SimState a(q0, VecQ::Zero(8)), b(q0, VecQ::Zero(8));
  run(a, ws1, 1500);
  run(b, ws2, 700);
  const SimState saved = b;
  run(b, ws2, 800);
  SimState c = saved;
  run(c, ws3, 800);
  EXPECT_TRUE(test::sameBits(a.q, b.q) && test::sameBits(a.v, b.v));
  EXPECT_TRUE(test::sameBits(a.q, c.q) && test::sameBits(a.v, c.v));
  EXPECT_EQ(a.t, c.t);
  EXPECT_GT((a.q - q0).norm(), 0.1);  // something happened
}

TEST(Simulator, RejectsBadSettingsAndStates) {
  const RbsfModel model(test::makeCell(ShapeKind::kEllipse, 3));
  SimulatorSettings bad;
  bad.time_step = 0.0;
  EXPECT_THROW(Simulator(model, bad), InputError);
  bad = {};
  bad.activation_distance = 1e-9;  // below the contact tolerance
  EXPECT_THROW(Simulator(model, bad), InputError);
  EXPECT_THROW(SimState(VecQ::Zero(7), VecQ::Zero(6)), InputError);
  const Simulator sim(model);
  SimulatorWorkspace ws3(3), ws4(4);
  SimState s3(VecQ::Zero(7), VecQ::Zero(7)), s4(VecQ::Zero(8), VecQ::Zero(8));
  EXPECT_THROW(sim.step(s4, VecU::Zero(4), ws3), std::invalid_argument);
  EXPECT_THROW(sim.step(s3, VecU::Zero(5), ws3), std::invalid_argument);
  EXPECT_THROW(sim.step(s3, VecU::Zero(4), ws4), std::invalid_argument);
  EXPECT_EQ(toString(ContactMode::kSlide), "slide");
}

}  // namespace
}  // namespace rbsf
