// The planner's decisive-modes rule (propagator.h): the propagator's verdict agrees with an
// independent re-simulation that watches every contact, plans keep the rule in every
// propagation step, and the plans it gives a tracking cell can repeat.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"
#include "sim_test_support.h"
#include "test_support.h"

namespace rbsf::planner {
using namespace rbsf::plan;  // the plan the planner makes
namespace {

const std::string kDefaultCell = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";

// The rule checked from the simulator's own reports, step by step (the test's oracle):
// after `settle` steps of each window of `window` steps, every contact keeps its mode and
// sticking contacts stay within margin * mu_s * f_n.
class RuleOracle {
 public:
  RuleOracle(const RbsfModel& model, const DecisiveModes& rule, int window)
      : mu_(model.cell().friction.mu_static), rule_(rule), window_(window) {}

  // Feed the report of the step numbered `k` (from 0) of the motion; false once broken.
  bool feed(long k, const StepReport& report, int m) {
    const long in_window = k % window_ + 1;  // steps done in this window
    if (in_window < rule_.settle_steps) return true;
    if (in_window == rule_.settle_steps) {
      for (int i = 0; i < m; ++i) held_[i] = report.contacts[i].mode;
      return true;
    }
    for (int i = 0; i < m; ++i) {
      const ContactStepReport& c = report.contacts[i];
      if (c.mode != held_[i]) return false;
      if (c.mode == ContactMode::kStick && std::abs(c.f_t) > rule_.cone_margin * mu_ * c.f_n)
        return false;
    }
    return true;
  }

 private:
  double mu_;
  DecisiveModes rule_;
  int window_;
  std::array<ContactMode, kMaxFingers> held_{};
};

class DecisiveModesTest : public ::testing::Test {
 protected:
  RbsfModel model{loadCell(kDefaultCell)};

  static Problem problem(double goal_deg) {
    Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = {goal_deg < -45.0 ? -0.1 : 0.1, 0.40, goal_deg * M_PI / 180.0};
    return p;
  }
  static PlannerSettings settings(std::uint32_t seed) {
    PlannerSettings s;
    s.seed = seed;
    s = test::withoutClock(s);
    s.max_propagations = 200000;  // the searches end at the goal well within it
    return s;
  }
};

TEST_F(DecisiveModesTest, PropagatorVerdictAgreesWithTheSimulatorsReports) {
  // From the part held at rest, a held tau: the holding tau with the base torque raised by
  // d. Small d turns everything together (phase C throughout); larger d makes a contact
  // break away, at first creeping in mid-window (refused), at larger d at once.
  ReorientationPlanner rp(model, settings(1));
  const PlannerSetup setup = rp.setup(problem(-15.0));
  const auto si = setup.simple_setup->getSpaceInformation();
  const int m = model.numFingers(), window = rp.settings().steps_per_control;
  const double h = rp.simulator().settings().time_step;
  const HoldingSolution hold = test::holdingAt(model, setup.q0);
  ASSERT_TRUE(hold.feasible);
  const SimPropagator lenient(si, rp.simulator(), *setup.space, DecisiveModes{false});

  ompl::base::State* start = si->allocState();
  ompl::base::State* result = si->allocState();
  ompl::control::Control* control = si->allocControl();
  setup.space->fromSim(SimState(setup.q0, VecQ::Zero(m + 4)), start);
  int kept = 0, broken = 0;
  SimulatorWorkspace ws(m);
  StepReport report;
  for (double d = 0.0; d <= 300.0; d += 5.0) {
    VecU tau = hold.tau;
    tau[layout::kTauTheta] += d;
    double* u = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
    for (int j = 0; j <= m; ++j) u[j] = tau[j];
    // Two windows, as propagateWhileValid would run them.
    RuleOracle oracle(model, rp.settings().decisive_modes, window);
    SimState sim(setup.q0, VecQ::Zero(m + 4));
    bool keeps = true;
    for (long k = 0; k < 2 * window && keeps; ++k) {
      rp.simulator().step(sim, tau, ws, &report);
      keeps = oracle.feed(k, report, m);
    }
    const bool valid = si->propagateWhileValid(start, control, 2, result) == 2;
    EXPECT_EQ(valid, keeps) << "base torque +" << d << " N m";
    (keeps ? kept : broken) += 1;
    // Without the rule the same steps count as long as the part is supported.
    lenient.propagate(start, control, window * h, result);
    EXPECT_TRUE(static_cast<SimStateSpace::StateType*>(result)->decisive) << d;
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(broken, 0);
  EXPECT_GT(setup.propagator->indecisive(), 0u);
  si->freeControl(control);
  si->freeState(result);
  si->freeState(start);
}

TEST_F(DecisiveModesTest, PlansKeepTheRuleInEveryPropagationStep) {
  ReorientationPlanner rp(model, settings(1));
  Plan plan;
  ASSERT_TRUE(rp.solve(problem(-30.0), plan));
  ASSERT_EQ(plan.status, plan::PlanStatus::kExact);
  const int m = model.numFingers();
  RuleOracle oracle(model, rp.settings().decisive_modes, rp.settings().steps_per_control);
  SimState sim(plan.q0, VecQ::Zero(m + 4));
  SimulatorWorkspace ws(m);
  StepReport report;
  long k = 0;
  for (const PlanSegment& seg : plan.segments) {
    ASSERT_EQ(seg.steps % rp.settings().steps_per_control, 0);
    for (int j = 0; j < seg.steps; ++j, ++k) {
      rp.simulator().step(sim, seg.tau, ws, &report);
      ASSERT_TRUE(oracle.feed(k, report, m)) << "step " << k;
    }
  }
  EXPECT_GT(k, 0);
}

TEST_F(DecisiveModesTest, BadRuleSettingsAreRefused) {
  ReorientationPlanner rp(model, settings(1));
  const PlannerSetup setup = rp.setup(problem(-15.0));
  const auto si = setup.simple_setup->getSpaceInformation();
  for (const DecisiveModes& bad :
       {DecisiveModes{true, -1, 0.9}, DecisiveModes{true, 2, 0.0}, DecisiveModes{true, 2, 1.5}}) {
    EXPECT_THROW(SimPropagator(si, rp.simulator(), *setup.space, bad), InputError);
  }
}

}  // namespace
}  // namespace rbsf::planner
