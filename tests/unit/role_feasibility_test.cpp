// Can the law do this step here? (role_feasibility.h): the answer for a slider's breakaway
// agrees with a closed-loop run of the law on the simulator from that configuration, on the
// nominal plant and at both ends of the cell's static-friction draws, for five pivot starts
// built for it; the support searches refuse the steps it refuses.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/control/role_feasibility.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/support/support_planner.h"

namespace rbsf {
namespace {

using planner::JigPose;
using planner::SupportGeometry;

Cell defaultCell() { return loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"); }

/// What a breakaway did in the plant: the slider slipped its planned way, or a tip planned
/// to stick slipped first, within the run.
struct Breakaway {
  bool slid = false;
  bool stuck_slipped = false;
};

/// The law (joint feedback, on the exact state) holding a stationary reference at q with
/// `roles` and the feed-forward `tau`, on `plant`, for 0.5 s. With `v0`, the reference
/// instead moves from q at v0 and slows evenly to rest at 1 s (the end of a run).
Breakaway runLaw(const RbsfModel& model, const RbsfModel& plant, const VecQ& q,
                 const ContactRoles& roles, const VecU& tau0, const VecQ& v0 = VecQ()) {
  const int n = static_cast<int>(q.size());
  const VecQ v_start = v0.size() == n ? v0 : VecQ::Zero(n);
  ReferenceTrajectory ref;
  ref.addKnot(0.0, q, v_start);
  ref.addKnot(1.0, q + 0.5 * v_start, VecQ::Zero(n));
  ref.addInputPiece(0.0, 1.0, tau0, VecU(), Phase::kP, roles);
  const SimulatorSettings settings;
  Sensing sensing = model.cell().sensing;
  sensing.part_pose.present = false;
  const FeedbackSchedule schedule(model, ref, sensing, settings);
  ControlLaw law(schedule);
  const Simulator sim(plant, settings);
  auto ws = std::make_unique<SimulatorWorkspace>(plant.numFingers());
  SimState s(q, VecQ::Zero(n));
  VecU tau;
  StepReport report;
  Breakaway out;
  for (long k = 0; k < 500 && !out.slid; ++k) {
    law.computeFromState(k * settings.time_step, s.q, s.v, tau);
    sim.step(s, tau, *ws, &report);
    for (int i = 0; i < plant.numFingers(); ++i) {
      const ContactStepReport& c = report.contacts[i];
      if (slipSign(roles[i]) != 0 && c.mode == ContactMode::kSlide &&
          slipSign(roles[i]) * c.slip > 0.0)
        out.slid = true;
      if (roles[i] == ContactRole::kStick && c.mode == ContactMode::kSlide && !out.slid)
        out.stuck_slipped = true;
    }
  }
  return out;
}

/// A pivot about the finger of `sticking` from the default placement tilted rigidly to
/// `theta_deg`, its part turning by one lattice step the way of `dpsi`, with the fingers of
/// `touching`: the configuration, roles, the balance's breakaway input and the law's answer.
struct PivotStart {
  VecQ q;
  ContactRoles roles{};
  VecU feedforward;
  RoleVerdict verdict;
  VecQ step;         ///< the pivot's first lattice step (configuration change)
  VecU run_balance;  ///< the run's own input at rest there (its sliders frictionless)
};

PivotStart pivotStart(const RbsfModel& model, double theta_deg, std::uint32_t touching,
                      std::uint32_t sticking = 0b100u, int dpsi = 1) {
  planner::SupportSearchSettings ss = planner::SupportPlannerSettings::defaultSearch();
  planner::SupportSearch search(model, ss);
  SupportGeometry& g = search.geometry();
  JigPose p0 = JigPose::fromWorld(Pose{0.1, 0.4, 0.0}, 0.0);
  p0.theta = theta_deg * M_PI / 180;
  const ContactSet set{touching, sticking};
  PivotStart out;
  const std::optional<VecQ> q = g.configuration(p0, set, true);
  EXPECT_TRUE(q.has_value());
  if (!q) return out;
  planner::PivotAnchor anchor;
  EXPECT_TRUE(search.anchorFor(p0, set, anchor));
  const std::optional<VecQ> q1 =
      g.configuration(g.pivotPose(anchor, p0.psi + dpsi * ss.angle_step, p0.theta), set, true);
  EXPECT_TRUE(q1.has_value());
  if (!q1) return out;
  const VecC slip = g.slipDirections(*q, *q1);
  ContactBalancer balancer(model, ss.support.balance);
  ModelData data(model.numFingers());
  out.q = *q;
  out.step = *q1 - *q;
  const VecQ zero = VecQ::Zero(q->size());
  out.run_balance = balancer.solve(*q, zero, zero, set, data).tau;
  out.feedforward = balancer.breakaway(*q, set, data, slip).tau;
  out.roles = planner::supportRoles(set, slip, model.numFingers());
  out.verdict = g.lawCheck(*q, set, slip, false, out.feedforward);
  return out;
}

/// The plants at the cell's static-friction draws' ends and the nominal one.
std::vector<Cell> frictionEnds();

/// Runs the law from `p` on every plant of frictionEnds(): the slider slips its way exactly
/// when `slides`, and a tip planned to stick slips first exactly when `stuck_slips`.
void expectOnEveryPlant(const RbsfModel& model, const PivotStart& p, bool slides,
                        bool stuck_slips) {
  for (const Cell& c : frictionEnds()) {
    const RbsfModel plant(c);
    const Breakaway b = runLaw(model, plant, p.q, p.roles, p.feedforward);
    EXPECT_EQ(b.slid, slides) << "mu_s " << c.friction.mu_static;
    EXPECT_EQ(b.stuck_slipped, stuck_slips) << "mu_s " << c.friction.mu_static;
  }
}

std::vector<Cell> frictionEnds() {
  const Cell nominal = defaultCell();
  std::vector<Cell> cells(3, nominal);
  cells[0].friction.mu_static *= 1.0 - nominal.uncertainty.static_friction;
  cells[2].friction.mu_static *= 1.0 + nominal.uncertainty.static_friction;
  return cells;
}

TEST(RoleFeasibility, ASliderOnTwoTipsBreaksLooseAsTheLawSays) {
  // Finger 1 lifted, the pivot on finger 3, finger 2 to slide, the base at -15 deg: the law
  // can pull the slider loose, and does on every plant, the pivot held.
  const RbsfModel model(defaultCell());
  const PivotStart p = pivotStart(model, -15.0, 0b110u);
  EXPECT_TRUE(p.verdict.feasible) << toString(p.verdict.refusal);
  EXPECT_EQ(rolesText(p.roles, 3)[0], 'L');
  expectOnEveryPlant(model, p, true, false);
}

TEST(RoleFeasibility, ASliderItsRunBringsToRestIsNotPulledLooseAgain) {
  // The slider of the test above, stuck, while the reference ends its run (its own input,
  // the planned slip under the loose sliders' floor and falling to rest). Stuck is where the
  // plan brings it, so the law does not pull it loose (a pull there started the slide again
  // and dropped parts at the ends of pivots); from rest (the test above) it does.
  const RbsfModel model(defaultCell());
  const PivotStart p = pivotStart(model, -15.0, 0b110u);
  ModelData data(model.numFingers());
  model.updateContacts(p.q, data);
  const int slider = 1;
  const double slip = data.T.col(slider).dot(p.step);
  ASSERT_GT(std::abs(slip), 1e-4);
  const double floor = ContactForceSettings().slip_speed;
  const VecQ v0 = p.step * (0.05 * floor / std::abs(slip));  // slows from 5 % of the floor
  for (const Cell& c : frictionEnds()) {
    const Breakaway b = runLaw(model, RbsfModel(c), p.q, p.roles, p.run_balance, v0);
    EXPECT_FALSE(b.slid) << "mu_s " << c.friction.mu_static;
    EXPECT_FALSE(b.stuck_slipped) << "mu_s " << c.friction.mu_static;
  }
}

TEST(RoleFeasibility, APivotsStuckTipDriftingByAStepsFrameChangeKeepsItsRole) {
  // A time step's sticking tip, read on the exact state at the step's end, slips by the
  // step's change of its frame (about 1e-5 m/s in a slow pivot). Read as a slip, the QP
  // would take the pivot frictionless and move the forces by newtons at once (a pivot of a
  // +60 deg turn dropped in the nominal run); the law's input must not notice it.
  const RbsfModel model(defaultCell());
  const PivotStart p = pivotStart(model, -15.0, 0b110u);
  ASSERT_EQ(rolesText(p.roles, 3)[2], 'S');
  const int n = static_cast<int>(p.q.size());
  ReferenceTrajectory ref;
  ref.addKnot(0.0, p.q, VecQ::Zero(n));
  ref.addKnot(1.0, p.q, VecQ::Zero(n));
  ref.addInputPiece(0.0, 1.0, p.run_balance, VecU(), Phase::kP, p.roles);
  Sensing sensing = model.cell().sensing;
  sensing.part_pose.present = false;
  const FeedbackSchedule schedule(model, ref, sensing, SimulatorSettings());
  ModelData data(model.numFingers());
  model.updateContacts(p.q, data);
  const double drift = 0.3 * schedule.settings().contacts.exact_slip_speed;
  ASSERT_GT(drift, 10.0 * SimulatorSettings().slip_tolerance);  // over the plant's tolerance
  // The least velocity with which the pivot's tip slips `drift` and the slider's tip neither
  // slips nor leaves, nor the pivot's.
  Eigen::MatrixXd A(4, n);
  A << data.T.col(1).transpose(), data.T.col(2).transpose(), data.G1.col(1).transpose(),
      data.G1.col(2).transpose();
  const Eigen::Vector4d b(0.0, drift, 0.0, 0.0);
  const VecQ v = A.transpose() * (A * A.transpose()).ldlt().solve(b);
  ASSERT_NEAR(data.T.col(2).dot(v), drift, 1e-12);
  VecU still, drifting;
  ControlLaw(schedule).computeFromState(0.0, p.q, VecQ::Zero(n), still);
  ControlLaw(schedule).computeFromState(0.0, p.q, v, drifting);
  EXPECT_LT((drifting - still).cwiseAbs().maxCoeff(), 0.5)
      << "still " << still.transpose() << "\ndrifting " << drifting.transpose();
}

TEST(RoleFeasibility, TheSameSliderBesideAThirdStuckTipCannotBreakLoose) {
  // The base level, all three tips touching (finger 1 planned to slide too): the squeeze the
  // pull needs is one no actuator steers; the law says no, and in the plant the sliders stay
  // stuck while the pivot slips first, on every plant.
  const RbsfModel model(defaultCell());
  const PivotStart p = pivotStart(model, 0.0, 0b111u);
  EXPECT_FALSE(p.verdict.feasible);
  EXPECT_EQ(p.verdict.refusal, RoleRefusal::kBreakaway);
  expectOnEveryPlant(model, p, false, true);
}

TEST(RoleFeasibility, APivotWhosePullIsJustOutsideItsMarginStaysStuck) {
  // Two tips, the base at +5 deg: the pull falls short of its margin by a few per cent of the
  // weight (the pivot's cone is at the law's limit); the law says no and the slider stays
  // stuck on every plant.
  const RbsfModel model(defaultCell());
  const PivotStart p = pivotStart(model, 5.0, 0b110u);
  EXPECT_FALSE(p.verdict.feasible);
  EXPECT_EQ(p.verdict.refusal, RoleRefusal::kBreakaway);
  EXPECT_GT(p.verdict.shortfall, 0.0);
  EXPECT_LT(p.verdict.shortfall, 0.05);
  expectOnEveryPlant(model, p, false, false);
}

TEST(RoleFeasibility, ASliderLevelWithThePivotStaysStuckHoweverTheLawPulls) {
  // Fingers 1 and 3 at one height (the default placement tilted to -15 deg, finger 2
  // lifted): the QP's predicted forces meet the pull, but the squeeze along the tips' line is
  // horizontal, felt by no actuator, and the plant uses it to keep finger 1 inside its cone.
  // The law says no, and the slider stays stuck on every plant.
  const RbsfModel model(defaultCell());
  const PivotStart p = pivotStart(model, -15.0, 0b101u);
  EXPECT_EQ(rolesText(p.roles, 3)[1], 'L');
  EXPECT_FALSE(p.verdict.feasible);
  EXPECT_EQ(p.verdict.refusal, RoleRefusal::kBreakaway);
  EXPECT_LE(p.verdict.shortfall, 1e-6);
  expectOnEveryPlant(model, p, false, false);
}

TEST(RoleFeasibility, TheSupportSearchRefusesABreakawayTheBalanceAloneWouldTake) {
  // Three tips at base +10 deg, the pivot on finger 1, fingers 2 and 3 to slide the negative
  // way: the balance LP can pull both sliders (it steers every internal force); the law's
  // predicted forces fall short of its pull, and in the plant the sliders stay stuck on every
  // plant. The search's breakaway check asks the law, so it refuses the step.
  const RbsfModel model(defaultCell());
  const PivotStart p = pivotStart(model, 10.0, 0b111u, 0b001u, -1);
  EXPECT_EQ(rolesText(p.roles, 3), "S--");
  EXPECT_FALSE(p.verdict.feasible);
  EXPECT_EQ(p.verdict.refusal, RoleRefusal::kBreakaway);
  expectOnEveryPlant(model, p, false, false);
  planner::SupportSearchSettings ss = planner::SupportPlannerSettings::defaultSearch();
  planner::SupportSearch search(model, ss);
  SupportGeometry& g = search.geometry();
  JigPose p0 = JigPose::fromWorld(Pose{0.1, 0.4, 0.0}, 0.0);
  p0.theta = 10.0 * M_PI / 180;
  const ContactSet set{0b111u, 0b001u};
  planner::PivotAnchor anchor;
  ASSERT_TRUE(search.anchorFor(p0, set, anchor));
  const std::optional<VecQ> q1 =
      g.configuration(g.pivotPose(anchor, p0.psi - ss.angle_step, p0.theta), set, true);
  ASSERT_TRUE(q1.has_value());
  const VecC slip = g.slipDirections(p.q, *q1);
  EXPECT_FALSE(g.breaksAway(p.q, set, slip));
  ss.support.law_check = false;
  planner::SupportSearch balance_only(model, ss);
  EXPECT_TRUE(balance_only.geometry().breaksAway(p.q, set, slip));
}

TEST(RoleFeasibility, TheSearchRefusesAHandOverTheLawCannotHoldHalfway) {
  // At the default placement tilted to -15 deg, from fingers 2 and 3 sticking to the pivot on
  // finger 3 with finger 1 sliding: each set holds the part at rest, but halfway through the
  // hand-over (all three touching, fingers 1 and 2 free) the law keeps the part only by
  // moving it, so the search refuses the switch by the law's rule; without the law's check
  // it takes it.
  const RbsfModel model(defaultCell());
  planner::SupportSearchSettings ss = planner::SupportPlannerSettings::defaultSearch();
  JigPose p0 = JigPose::fromWorld(Pose{0.1, 0.4, 0.0}, 0.0);
  p0.theta = -15.0 * M_PI / 180;
  const ContactSet from{0b110u, 0b110u}, to{0b101u, 0b100u};
  planner::SupportSearch search(model, ss);
  planner::SupportStep rest, next;
  ASSERT_TRUE(search.restAt(p0, from, rest));
  ASSERT_TRUE(search.geometry().check(p0, to).valid);
  planner::PivotAnchor anchor;
  ASSERT_TRUE(search.anchorFor(p0, to, anchor));
  EXPECT_FALSE(search.stepTo(rest, p0, to, anchor, next));
  EXPECT_EQ(search.refusal(), planner::SupportRule::kLaw);
  ss.support.law_check = false;
  planner::SupportSearch balance_only(model, ss);
  EXPECT_TRUE(balance_only.stepTo(rest, p0, to, anchor, next));
}

}  // namespace
}  // namespace rbsf
