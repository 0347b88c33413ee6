// docs/library.md's execution recipe, compiled and run: the code between the two "[recipe]"
// lines below is the page's block, character for character (ThePageShowsThisCode). Run on
// the project's simulator as the cell, with exact sensors, it is the certificate's trial
// without draws, step for step: on a support plan (joint feedback) to its end, on a
// kinodynamic plan (part poses late at 100 Hz) until the executor's status holds the part
// (the trial's law runs on); a plan for another
// cell stops it at loadFile().
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "rbsf/controller/reorientation_controller.h"
#include "rbsf/dynamics/control/sensor_model.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/executor/plan_runner.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_reference.h"
#include "rbsf/plan/trial.h"
#include "support_plan_file.h"
#include "trajopt_support.h"

namespace rbsf::controller {
namespace {

const std::string kSourceDir = RBSF_SOURCE_DIR;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The project's simulator as the cell a controller drives: the nominal plant started
/// where the plan starts, its sensors exact (the cell's rate and latency, no noise), as in
/// the certificate's trial without draws (plan::nominalDraw, plan::runTrial).
class SimulatedCell {
 public:
  SimulatedCell(const RbsfModel& model, const plan::Plan& plan)
      : sim_(model, plan.simulator),
        ws_(model.numFingers()),
        sensors_(plan::lawSensing(model.cell().sensing, plan), plan.simulator.time_step, 0,
                 /*noise=*/false, Vec2::Zero()),
        state_(plan::nominalDraw(model.cell(), plan).q0,
               VecQ::Zero(static_cast<int>(plan.q0.size()))) {}

  /// \brief theta, l_1..l_m at the present tick.
  void readJoints(VecU& joints) { sensors_.joints(state_.q, joints); }
  /// \brief The next part pose handed over at this tick, if any.
  bool readPartPose(double& stamp, Pose& pose) {
    if (!polled_) {
      polled_ = true;
      sensors_.partPose(tick_, state_.q, [&](double s, const Pose& p) {
        queue_.push_back({s, p});
      });
    }
    if (queue_.empty()) return false;
    stamp = queue_.front().first;
    pose = queue_.front().second;
    queue_.erase(queue_.begin());
    return true;
  }
  /// \brief Hold `tau` over one step; the next tick.
  void apply(const VecU& tau) {
    sim_.step(state_, tau, ws_);
    ++tick_;
    polled_ = false;
    states_.push_back(state_.q);
  }
  /// \brief The cell's own logic hears that the run holds the part (counted here).
  void report(const ExecutionStatus& status) {
    if (status.verdict == ExecutionVerdict::kHolding) ++held_ticks_;
  }
  long heldTicks() const { return held_ticks_; }
  const VecQ& q() const { return state_.q; }
  /// \brief The state after each tick.
  const std::vector<VecQ>& states() const { return states_; }

 private:
  Simulator sim_;
  SimulatorWorkspace ws_;
  SensorModel sensors_;
  SimState state_;
  long tick_ = 0;
  long held_ticks_ = 0;
  bool polled_ = false;
  std::vector<std::pair<double, Pose>> queue_;
  std::vector<VecQ> states_;
};

/// The recipe as a function: 2 when the plan is refused, 0 after the plan and `settle`.
int runPlanFile(const std::string& cell_file, const std::string& plan_file, SimulatedCell& cell,
                double settle) {
  // [recipe]
  rbsf::executor::PlanRunner runner(cell_file);  // throws rbsf::InputError
  std::string why;
  if (!runner.loadFile(plan_file, &why)) {  // another cell's plan or evidence, not certified
    std::fprintf(stderr, "%s\n", why.c_str());
    return 2;
  }
  double duration = 0.0;
  rbsf::VecQ q0;
  runner.publishedPlan(duration, q0);  // the cell starts at rest at q0 (the plan's start)
  const double h = runner.timeStep();  // the loop's period: the plan's time step
  rbsf::VecU joints(runner.model().controlDim()), tau;
  rbsf::ExecutionStatus status;
  double stamp = 0.0;
  rbsf::Pose pose;
  runner.start();
  const long ticks = std::lround((duration + settle) / h);
  for (long k = 0; k < ticks; ++k) {  // the loop thread; plan time t = k h
    const double t = h * static_cast<double>(k);
    cell.readJoints(joints);                  // theta, l_1..l_m measured now
    while (cell.readPartPose(stamp, pose)) {  // each part pose that arrived, when sensed,
      runner.addPartPose(stamp, pose);        // stamped when it was taken
    }
    runner.step(t, joints, tau, &status);  // the plan's law behind its guard, and its status
    cell.apply(tau);                       // held until the next tick
    if (status.verdict == rbsf::ExecutionVerdict::kHolding) cell.report(status);
  }
  // [recipe]
  return 0;
}

TEST(ExecutionRecipe, ThePageShowsThisCode) {
  // The recipe's lines in this file, less the function body's indent.
  const std::string self = slurp(kSourceDir + "/tests/controller/recipe_test.cpp");
  const std::string marker = "  // [recipe]\n";
  const std::size_t a = self.find(marker), b = self.find(marker, a + 1);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  std::istringstream lines(self.substr(a + marker.size(), b - a - marker.size()));
  std::string code;
  for (std::string line; std::getline(lines, line);)
    code += (line.rfind("  ", 0) == 0 ? line.substr(2) : line) + "\n";
  // The page's block after the line that names this file.
  const std::string page = slurp(kSourceDir + "/docs/library.md");
  const std::size_t named = page.find("<!-- recipe: tests/controller/recipe_test.cpp -->");
  ASSERT_NE(named, std::string::npos) << "docs/library.md lost its recipe marker";
  const std::size_t open = page.find("```cpp\n", named);
  ASSERT_NE(open, std::string::npos);
  const std::size_t close = page.find("```\n", open + 7);
  ASSERT_NE(close, std::string::npos);
  EXPECT_EQ(page.substr(open + 7, close - open - 7), code)
      << "docs/library.md's recipe differs from tests/controller/recipe_test.cpp's";
}

TEST(ExecutionRecipe, RunsAPlanFileAsTheCertificatesTrialWithoutDraws) {
  const RbsfModel model(loadCell(kDefaultCell));
  const plan::Plan plan = plan::readPlanJson(planFile()).plan;
  std::vector<TrajectorySample> trace;
  const plan::TrialOutcome nominal =
      plan::traceTrial(model, plan, plan::CertificateSettings{}, -1, trace);
  ASSERT_TRUE(nominal.success) << nominal.failure;
  SimulatedCell cell(model, plan);
  const double settle = plan::CertificateSettings{}.feedback.timing.settle_time;
  ASSERT_EQ(runPlanFile(kDefaultCell, planFile(), cell, settle), 0);
  ASSERT_EQ(static_cast<double>(trace.size()),
            std::round((plan.duration() + settle) / plan.simulator.time_step));
  EXPECT_LT((cell.q() - trace.back().q).cwiseAbs().maxCoeff(), 1e-9) << cell.q().transpose() << "\n"
                                                                     << trace.back().q.transpose();
  EXPECT_LT(std::hypot(cell.q()[0] - plan.goal.x, cell.q()[1] - plan.goal.y), 0.01);
  EXPECT_EQ(cell.heldTicks(), 0);
}

TEST(ExecutionRecipe, RunsAPartFeedbackPlanAsItsTrialStepForStep) {
  // The part-pose half of the loop: a kinodynamic plan (part feedback; part poses at
  // 100 Hz, 10 ms late). Its nominal trial loses the part after its first release, and
  // stops there; until then the recipe's run is the trial's, step for step. The plan is
  // marked certified so that loadFile takes it: this test is about the loop, not the verdict.
  const RbsfModel& model = trajopt::test::defaultModel();
  const plan::Plan plan = trajopt::test::shortPlan();
  ASSERT_FALSE(plan.joint_feedback);
  plan::CertificateSettings one;
  one.trials = 1;
  plan::PlanRecord record;
  record.plan = plan;
  record.certificate = plan::certify(model, plan, one);
  record.certificate.certified = true;
  const std::string file =
      ::testing::TempDir() + "recipe_kinodynamic_" + std::to_string(getpid()) + ".json";
  plan::writePlanJson(record, file);
  std::vector<TrajectorySample> trace;
  const plan::TrialOutcome o =
      plan::traceTrial(model, plan, plan::CertificateSettings{}, -1, trace);
  ASSERT_GT(trace.size(), 100u);
  SimulatedCell cell(model, plan);
  ASSERT_EQ(runPlanFile(kDefaultCell, file, cell, 0.0), 0);
  ASSERT_GE(cell.states().size(), trace.size());
  // The executor holds the part from the tick after its status first says "leaving"; the
  // trial's law does not (a certificate judges the law): the same run up to that tick.
  const double h = plan.simulator.time_step;
  const std::size_t same =
      o.leaving_time < 0.0
          ? trace.size()
          : std::min(trace.size(), static_cast<std::size_t>(std::lround(o.leaving_time / h) + 1));
  ASSERT_GT(same, 100u);
  double worst = 0.0;
  for (std::size_t k = 0; k < same; ++k)
    worst = std::max(worst, (cell.states()[k] - trace[k].q).cwiseAbs().maxCoeff());
  EXPECT_LT(worst, 1e-9) << "over " << same << " steps";
  // Held from the tick after the leaving verdict to the end, and the cell heard of it.
  if (o.leaving_time >= 0.0) {
    EXPECT_EQ(cell.heldTicks(), static_cast<long>(cell.states().size()) - static_cast<long>(same));
  }
}

TEST(ExecutionRecipe, StopsAtLoadFileForAnotherCellsPlan) {
  const RbsfModel model(loadCell(kDefaultCell));
  const plan::Plan plan = plan::readPlanJson(planFile()).plan;
  SimulatedCell cell(model, plan);
  // The heavy cell's part weighs more: the plan is not for it.
  EXPECT_EQ(runPlanFile(kSourceDir + "/cells/heavy.yaml", planFile(), cell, 0.0), 2);
}

}  // namespace
}  // namespace rbsf::controller
