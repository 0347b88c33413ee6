// The optimiser's phase schedule and initial guess on a short real plan (the planner's 15
// degree turn, phases C P U with a finger lifting off inside U): runs follow the simulated
// contact modes, and the guess's held forces are the simulator's, so its dynamics defects
// are small.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/trajopt/schedule.h"
#include "rbsf/trajopt/trajectory_problem.h"
#include "trajopt_support.h"

namespace rbsf::trajopt {
namespace {

using ModeKey = std::array<int, kMaxFingers>;

// Each segment's majority contact modes, by a re-simulation of the plan written here.
std::vector<ModeKey> segmentModes(const RbsfModel& model, const plan::Plan& plan) {
  const Simulator sim(model, plan.simulator);
  SimulatorWorkspace ws(model.numFingers());
  StepReport report;
  SimState state(plan.q0, VecQ::Zero(plan.q0.size()));
  std::vector<ModeKey> out;
  for (const plan::PlanSegment& seg : plan.segments) {
    std::array<std::array<int, 3>, kMaxFingers> count{};
    for (int k = 0; k < seg.steps; ++k) {
      sim.step(state, seg.tau, ws, &report);
      for (int i = 0; i < model.numFingers(); ++i)
        ++count[i][static_cast<int>(report.contacts[i].mode)];
    }
    ModeKey key{};
    for (int i = 0; i < model.numFingers(); ++i)
      key[i] =
          static_cast<int>(std::max_element(count[i].begin(), count[i].end()) - count[i].begin());
    out.push_back(key);
  }
  return out;
}

TEST(TrajoptSchedule, SplitRunsHoldOnePhaseAndOneSimulatedModePerContact) {
  const RbsfModel& model = test::defaultModel();
  const plan::Plan& plan = test::shortPlan();
  const ScheduleResult split_built = buildSchedule(model, plan, 60, RunCut::kContactModes);
  ASSERT_TRUE(split_built.ok()) << split_built.error;
  const ScheduleResult letters_built = buildSchedule(model, plan, 60, RunCut::kPhaseLetters);
  ASSERT_TRUE(letters_built.ok()) << letters_built.error;
  const Schedule& split = split_built.schedule;
  const Schedule& letters = letters_built.schedule;
  // The fixture's U run holds a lift-off, so splitting adds a run.
  ASSERT_GT(split.runs.size(), letters.runs.size());

  const std::vector<ModeKey> modes = segmentModes(model, plan);
  // Segment s belongs to the run whose [start, start + duration) holds its start time.
  std::size_t run = 0;
  double t = 0.0;
  std::vector<ModeKey> run_key(split.runs.size());
  std::vector<bool> seen(split.runs.size(), false);
  for (std::size_t s = 0; s < plan.segments.size(); ++s) {
    while (run + 1 < split.runs.size() && t >= split.runs[run + 1].start - 1e-9) ++run;
    EXPECT_EQ(plan.segments[s].phase, split.runs[run].phase) << "segment " << s;
    if (!seen[run]) run_key[run] = modes[s];
    seen[run] = true;
    EXPECT_EQ(modes[s], run_key[run]) << "segment " << s << " in run " << run;
    t += plan.segments[s].duration;
  }
  double total = 0.0;
  for (std::size_t j = 0; j < split.runs.size(); ++j) {
    total += split.runs[j].duration;
    ASSERT_TRUE(seen[j]) << "run " << j << " holds no segment";
    if (j > 0) {  // maximal: neighbours differ in letter or modes
      EXPECT_TRUE(split.runs[j].phase != split.runs[j - 1].phase || run_key[j] != run_key[j - 1]);
    }
    if (split.runs[j].phase != Phase::kU) continue;
    for (int i = 0; i < model.numFingers(); ++i)  // U: off where separated, else sliding
      EXPECT_EQ(split.runs[j].role[i], run_key[j][i] == static_cast<int>(ContactMode::kSeparated)
                                           ? ContactRole::kOff
                                           : ContactRole::kSlide)
          << "run " << j << " finger " << i;
  }
  EXPECT_NEAR(total, plan.duration(), 1e-9);

  // Too few intervals for the finer runs: one run per phase letter, as without splitting.
  const ScheduleResult coarse =
      buildSchedule(model, plan, 2 * static_cast<int>(letters.runs.size()), RunCut::kContactModes);
  ASSERT_TRUE(coarse.ok()) << coarse.error;
  EXPECT_EQ(coarse.schedule.runs.size(), letters.runs.size());
}

TEST(TrajoptSchedule, ErrorsComeBackAsValuesWithNoSchedule) {
  const RbsfModel& model = test::defaultModel();
  const ScheduleResult empty = buildSchedule(model, plan::Plan{}, 60, RunCut::kPhaseLetters);
  EXPECT_FALSE(empty.ok());
  EXPECT_EQ(empty.error, "the plan has no segments");
  EXPECT_TRUE(empty.schedule.runs.empty());

  // One interval is fewer than 2 per run for any plan.
  const ScheduleResult few = buildSchedule(model, test::shortPlan(), 1, RunCut::kPhaseLetters);
  EXPECT_FALSE(few.ok());
  EXPECT_NE(few.error.find("fewer than 2 per phase run"), std::string::npos) << few.error;
  EXPECT_TRUE(few.schedule.runs.empty());
  EXPECT_EQ(few.schedule.intervals(), 0);
}

TEST(TrajoptInitialGuess, KnotForcesAreTheSimulatorsSoTheObjectsDynamicsDefectsAreSmall) {
  const RbsfModel& model = test::defaultModel();
  OptimizerSettings settings;
  settings.knots = 30;
  const TrajectoryProblem problem(model, test::shortPlan(), settings);
  ASSERT_TRUE(problem.ok()) << problem.why();
  const Eigen::VectorXd z = problem.variables().initialGuess();
  const DecisionLayout& dl = problem.layout();
  const int n = model.configDim(), m = model.numFingers();

  const ConstraintSet* collocation = nullptr;
  for (const auto& set : problem.constraints())
    if (set->name() == "collocation") collocation = set.get();
  ASSERT_NE(collocation, nullptr);
  // Median over intervals of the largest of the object's six rows (D_q and D_v of x, y, phi:
  // rows 2n k + {0, n} + {x, y, phi}, collocation_constraint.h; units of its weight).
  auto medianObjectDefect = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd g(collocation->rows());
    collocation->values(at, g);
    std::vector<double> worst;
    for (int k = 0; k < dl.intervals(); ++k) {
      double w = 0.0;
      for (int row : {0, n})
        for (int c : {layout::kX, layout::kY, layout::kPhi})
          w = std::max(w, std::abs(g[2 * n * k + row + c]));
      worst.push_back(w);
    }
    std::nth_element(worst.begin(), worst.begin() + worst.size() / 2, worst.end());
    return worst[worst.size() / 2];
  };
  Eigen::VectorXd no_friction = z, no_forces = z;
  for (int k = 0; k < dl.knots(); ++k) {
    no_friction.segment(dl.ft(k), m).setZero();
    no_forces.segment(dl.ft(k), m).setZero();
    no_forces.segment(dl.fn(k), m).setZero();
  }
  // Measured: 0.056 at the guess, 0.118 without its friction, 1.01 without any force. The
  // guess's forces, friction included, are the ones that balance the object's motion.
  const double guess = medianObjectDefect(z);
  EXPECT_LT(guess, 0.1);
  EXPECT_LT(guess, 0.6 * medianObjectDefect(no_friction));
  EXPECT_LT(guess, 0.1 * medianObjectDefect(no_forces));

  // Sticking contacts carry their friction from the start.
  double max_ft = 0.0;
  for (int k = 0; k < dl.knots(); ++k)
    for (int i = 0; i < m; ++i)
      if (problem.schedule().forceRole(k, i) == ContactRole::kStick)
        max_ft = std::max(max_ft, std::abs(z[dl.ft(k) + i]));
  EXPECT_GT(max_ft, 1.0);
}

}  // namespace
}  // namespace rbsf::trajopt
