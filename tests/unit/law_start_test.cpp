// The law's first ticks (control_law.h): with exact sensors on the nominal plant, started
// where the plan starts (plan::nominalDraw), every input stays within its limit, the law
// demands no more than a limit, and every contact the plan relies on stays closed through
// the first 100 ms: of support plans (joint feedback; finger 1 lifted at the start, so an
// estimate that put the part on every finger would let it fall), and of a kinodynamic plan
// (part feedback) past its first release, where the part-feedback estimate stays on the
// plant.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "rbsf/dynamics/control/control_law.h"
#include "rbsf/dynamics/control/sensor_model.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/plan/trial.h"
#include "rbsf/planner/support/support_planner.h"
#include "trajopt_support.h"

namespace rbsf {
namespace {

/// What the first ticks of a run did.
struct StartLog {
  double worst_input = 0.0;     ///< max over ticks and inputs of |tau_j| / limit_j
  double worst_demand = 0.0;    ///< the same of the law's demand before its QP
  int clamped_ticks = 0;        ///< ticks compute() reported clamped
  int opened = 0;               ///< ticks a relied-on contact (S, +, -) was separated
  int role_changes = 0;         ///< ticks whose roles differ from the tick before
  double worst_estimate = 0.0;  ///< max |x_hat - x| over the part's pose [m, rad]
  int ticks = 0;
};

/// The first `duration` seconds of a run.
StartLog firstTicks(const RbsfModel& model, const plan::Plan& plan, double duration) {
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
    if (n > 0 && roles != schedule.roles(schedule.knotAt(t - h))) ++log.role_changes;
    sensors.joints(state.q, joints);
    sensors.partPose(n, state.q, [&](double stamp, const Pose& p) { law.addPartPose(stamp, p); });
    log.clamped_ticks += law.compute(t, joints, tau) ? 1 : 0;
    for (int j = 0; j < nu; ++j) {
      log.worst_input = std::max(log.worst_input, std::abs(tau[j]) / limit[j]);
      log.worst_demand = std::max(log.worst_demand, std::abs(law.demand()[j]) / limit[j]);
    }
    VecQ q_hat, v_hat;
    law.estimate(q_hat, v_hat);
    log.worst_estimate =
        std::max(log.worst_estimate, (q_hat - state.q).head<3>().cwiseAbs().maxCoeff());
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

StartLog expectCalmStart(const plan::Plan& plan, const char* what) {
  const StartLog log = firstTicks(trajopt::test::defaultModel(), plan, 0.1);
  EXPECT_EQ(log.clamped_ticks, 0) << what;
  EXPECT_LT(log.worst_input, 1.0) << what;
  EXPECT_LT(log.worst_demand, 1.0) << what;
  EXPECT_EQ(log.opened, 0) << what;
  EXPECT_EQ(log.ticks, 100) << what;
  return log;
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

TEST(LawStart, AKinodynamicPlansFirstTicksStayWithinTheLimitsPastItsFirstRelease) {
  // Phase C for 60 ms, then finger 2 is released to slide (roles L S S to L - S) and the
  // part pivots on finger 3. The estimate, corrected by every joint reading and by the
  // camera's late samples, stays on the plant through the release.
  const StartLog log = expectCalmStart(trajopt::test::shortPlan(), "kinodynamic -15 deg");
  EXPECT_GE(log.role_changes, 1) << "the first 100 ms should hold a change of roles";
  EXPECT_LT(log.worst_estimate, 1e-5);
}

TEST(LawStart, SupportPlansFirstTicksStayWithinTheLimitsAndKeepTheirContacts) {
  expectCalmStart(supportTurn(-15.0), "support -15 deg");
  expectCalmStart(supportTurn(-30.0), "support -30 deg");
}

}  // namespace
}  // namespace rbsf
