// A cell controller runs the plan file it is given (ReorientationController::loadFile; the
// loop itself is docs/library.md's recipe, recipe_test.cpp): the former recipe's law (the
// cell's sensing instead of the plan's) does not hold the plan's part; a plan made for
// another cell is refused, naming what differs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_fit.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/plan/trial.h"
#include "support_plan_file.h"

namespace rbsf::controller {
namespace {

TEST(LoadPlan, TheCellsSensingInsteadOfThePlansDoesNotHoldASupportPlansPart) {
  // The former recipe built the law on the cell's sensing: on this cell, which senses the
  // part, the part-feedback law, fed exact poses every millisecond.
  const RbsfModel model(loadCell(kDefaultCell));
  const plan::Plan plan = plan::readPlanJson(planFile()).plan;
  ASSERT_TRUE(model.cell().sensing.part_pose.present);
  const FeedbackSchedule wrong(model, plan::makeReference(plan), model.cell().sensing,
                               plan.simulator);
  ControlLaw law(wrong);
  const Simulator sim(model, plan.simulator);
  SimulatorWorkspace ws(model.numFingers());
  const VecQ q0 = restingConfiguration(model, plan.start, plan.start_theta);
  SimState state(q0, VecQ::Zero(q0.size()));
  VecU joints(model.controlDim()), tau;
  const double h = plan.simulator.time_step;
  const long steps = std::lround(wrong.holdEnd() / h);
  for (long k = 0; k < steps && state.q.allFinite(); ++k) {
    for (int j = 0; j < joints.size(); ++j) joints[j] = state.q[layout::inputToConfig(j)];
    law.addPartPose(k * h, Pose{state.q[layout::kX], state.q[layout::kY], state.q[layout::kPhi]});
    law.compute(k * h, joints, tau);
    sim.step(state, tau, ws);
  }
  const bool far = !state.q.allFinite() || std::hypot(state.q[layout::kX] - plan.goal.x,
                                                      state.q[layout::kY] - plan.goal.y) > 0.01;
  EXPECT_TRUE(far) << state.q.transpose();
}

TEST(LoadPlan, APlanForAnotherCellIsRefusedNamingWhatDiffers) {
  const plan::PlanRecord record = plan::readPlanJson(planFile());
  const plan::Plan& plan = record.plan;
  ASSERT_TRUE(plan.cell.recorded);
  const Cell base = loadCell(kDefaultCell);
  auto refusal = [&](Cell cell) {
    ReorientationController c(std::move(cell));
    std::string why;
    EXPECT_FALSE(c.load(record, &why));
    EXPECT_EQ(c.status(), ControllerStatus::kIdle);
    EXPECT_EQ(c.planId(), 0u);
    return why;
  };
  Cell heavier = base;
  heavier.object.mass *= 1.1;
  EXPECT_NE(refusal(heavier).find("the part's mass"), std::string::npos) << refusal(heavier);
  Cell moved = base;
  moved.fingers[1].r += 0.01;
  EXPECT_NE(refusal(moved).find("finger 2's offset"), std::string::npos) << refusal(moved);
  Cell four = base;
  four.fingers.push_back(four.fingers.back());
  four.fingers.back().r += 0.1;
  EXPECT_NE(refusal(four).find("3 fingers in the plan, 4 in this cell"), std::string::npos);
  // Without the record, the tips at the start still tell another part's shape.
  plan::PlanRecord unrecorded = record;
  unrecorded.plan.cell = plan::PlanCell{};
  Cell other_shape = loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/circle.yaml");
  other_shape.fingers = base.fingers;
  other_shape.object.mass = base.object.mass;
  ReorientationController c(other_shape);
  std::string why;
  EXPECT_FALSE(c.load(unrecorded, &why));
  EXPECT_NE(why.find("m from this cell's part"), std::string::npos) << why;
  // A plan whose certificate failed: refused unless accepted.
  plan::PlanRecord failed = record;
  failed.certificate.certified = false;
  ReorientationController strict(base);
  EXPECT_FALSE(strict.load(failed, &why));
  EXPECT_NE(why.find("not certified"), std::string::npos) << why;
  EXPECT_TRUE(strict.load(failed, &why, /*accept_uncertified=*/true)) << why;
  // A file that is no plan: the reader's message.
  EXPECT_FALSE(c.loadFile(kDefaultCell, &why));
  EXPECT_FALSE(why.empty());
  // And the plan's own cell takes it.
  ReorientationController same(base);
  EXPECT_TRUE(same.load(record, &why)) << why;
}

TEST(LoadPlan, APlanWhoseEvidenceIsAnotherCellsIsRefusedUnlessAccepted) {
  // The same part and fingers with other friction or uncertainty: the plan fits, but its
  // certificate speaks for another cell.
  const plan::PlanRecord record = plan::readPlanJson(planFile());
  ASSERT_TRUE(record.plan.cell.friction_recorded);
  ASSERT_TRUE(record.certificate.ran);
  const Cell base = loadCell(kDefaultCell);
  auto refusal = [&](Cell cell) {
    executor::PlanRunner runner(std::move(cell));
    std::string why;
    EXPECT_FALSE(runner.load(record, &why));
    EXPECT_EQ(runner.planId(), 0u);
    executor::LoadOptions accept;
    accept.accept_other_evidence = true;
    std::string none;
    EXPECT_TRUE(runner.load(record, &none, accept)) << none;
    return why;
  };
  auto expectRefused = [&](Cell cell, const std::string& names) {
    const std::string why = refusal(std::move(cell));
    EXPECT_NE(why.find(names), std::string::npos) << why;
  };
  Cell slippery = base;
  slippery.friction.mu_static = 0.3;
  expectRefused(slippery, "static friction mu_s is 0.5 in the plan, 0.3 in this cell");
  Cell kinetic = base;
  kinetic.friction.mu_kinetic = 0.5;
  expectRefused(kinetic, "kinetic friction mu_k");
  Cell wider = base;
  wider.uncertainty.mass = 0.3;
  expectRefused(wider, "uncertainty.mass is 0.05 in the plan, 0.3 in this cell");
  Cell blind = base;
  blind.sensing.part_pose.present = false;
  expectRefused(blind, "this cell does not see it");
  Cell late = base;
  late.sensing.part_pose.latency = 0.05;
  expectRefused(late, "latency");
  // Its own cell takes it without being told.
  executor::PlanRunner same(base);
  std::string why;
  EXPECT_TRUE(same.load(record, &why)) << why;
  // The facade refuses it the same way.
  ReorientationController facade(slippery);
  EXPECT_FALSE(facade.load(record, &why));
  EXPECT_NE(why.find("static friction"), std::string::npos) << why;
}

}  // namespace
}  // namespace rbsf::controller
