// The law's first ticks (control_law.h): with exact sensors on the nominal plant, started
// where the plan starts (plan::nominalDraw), every input stays within its limit, the law
// demands no more than a limit, and every contact the plan relies on stays closed: through
// the first 100 ms of support plans (joint feedback; finger 1 lifted at the start, so an
// estimate that put the part on every finger would let it fall), and on a kinodynamic plan
// (part feedback) until its roles first change: past its first release the part-feedback
// estimate leaves even an exact plant, which this test does not cover.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "rbsf/dynamics/control_law.h"
#include "rbsf/dynamics/sensor_model.h"
#include "rbsf/dynamics/simulator.h"
#include "rbsf/dynamics/state_layout.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/plan/trial.h"
#include "rbsf/planner/support_planner.h"
#include "trajopt_support.h"

namespace rbsf {
namespace {

/// What the first ticks of a run did.
struct StartLog {
  double worst_input = 0.0;   ///< max over ticks and inputs of |tau_j| / limit_j
  double worst_demand = 0.0;  ///< the same of the law's demand before its QP
  int clamped_ticks = 0;      ///< ticks compute() reported clamped
  int opened = 0;             ///< ticks a relied-on contact (S, +, -) was separated
  int ticks = 0;
};

/// The first `duration` seconds of a run, or up to the first change of the roles the law
/// reads when `until_roles_change`.
StartLog firstTicks(const RbsfModel& model, const plan::Plan& plan, double duration,
                    bool until_roles_change) {
  const FeedbackSchedule schedule(model, plan::makeReference(plan),
                                  plan::lawSensing(model.cell().sensing, plan), plan.simulator);
  const plan::TrialDraw draw = plan::nominalDraw(model.cell(), plan);
  const Simulator sim(model, plan.simulator);
  auto ws = std::make_unique<SimulatorWorkspace>(model.numFingers());
  ControlLaw law(schedule);
  const double h = plan.simulator.time_step;
  SensorModel sensors(schedule.sensing(), h, draw.noise_seed, /*noise=*/false, draw.com_offset);
  SimState state(draw.q0, VecQ::Zero(draw.q0.size()));
  const int m = model.numFingers(), nu = model.controlDim();
  VecU limit(nu), joints(nu), tau(nu);
  for (int j = 0; j < nu; ++j) limit[j] = model.cell().inputLimit(j);
  StartLog log;
  StepReport report;
  const long steps = std::lround(duration / h);
  for (long n = 0; n < steps; ++n) {
    const double t = static_cast<double>(n) * h;
    const ContactRoles& roles = schedule.roles(schedule.knotAt(t));
    if (until_roles_change && roles != schedule.roles(0)) break;
    sensors.joints(state.q, joints);
    sensors.partPose(n, state.q, [&](double stamp, const Pose& p) { law.addPartPose(stamp, p); });
    log.clamped_ticks += law.compute(t, joints, tau) ? 1 : 0;
    for (int j = 0; j < nu; ++j) {
      log.worst_input = std::max(log.worst_input, std::abs(tau[j]) / limit[j]);
      log.worst_demand = std::max(log.worst_demand, std::abs(law.demand()[j]) / limit[j]);
    }
    sim.step(state, tau, *ws, &report);
    for (int i = 0; i < m; ++i) {
      const bool relied = roles[i] == ContactRole::kStick || slipSign(roles[i]) != 0;
      if (relied && report.contacts[i].mode == ContactMode::kSeparated) {
        ++log.opened;
        break;
      }
    }
    ++log.ticks;
  }
  return log;
}

/// \return the ticks run.
int expectCalmStart(const plan::Plan& plan, const char* what, bool until_roles_change = false) {
  const StartLog log = firstTicks(trajopt::test::defaultModel(), plan, 0.1, until_roles_change);
  EXPECT_EQ(log.clamped_ticks, 0) << what;
  EXPECT_LT(log.worst_input, 1.0) << what;
  EXPECT_LT(log.worst_demand, 1.0) << what;
  EXPECT_EQ(log.opened, 0) << what;
  return log.ticks;
}

plan::Plan supportTurn(double degrees) {
  planner::SupportPlanner planner(trajopt::test::defaultModel(), planner::SupportPlannerSettings{});
  planner::Problem p;
  p.start = {0.1, 0.40, 0.0};
  p.goal = {0.1, 0.40, degrees * M_PI / 180.0};
  plan::Plan out;
  if (!planner.solve(p, out)) throw std::runtime_error(planner.message());
  return out;
}

TEST(LawStart, AKinodynamicPlansTicksBeforeItsRolesChangeStayWithinTheLimits) {
  // Its first roles hold for 60 ms (phase C), then a tip is released (phase P).
  EXPECT_GE(expectCalmStart(trajopt::test::shortPlan(), "kinodynamic -15 deg", true), 40);
}

TEST(LawStart, SupportPlansFirstTicksStayWithinTheLimitsAndKeepTheirContacts) {
  EXPECT_EQ(expectCalmStart(supportTurn(-15.0), "support -15 deg"), 100);
  EXPECT_EQ(expectCalmStart(supportTurn(-30.0), "support -30 deg"), 100);
}

}  // namespace
}  // namespace rbsf
