// A cell that executes plan files with rbsf::executor alone (no planner, no optimiser):
// reads a cell and a plan file, loads the plan into a PlanRunner (checked against the cell:
// its fit and its evidence) and runs it on the nominal simulator with exact sensors, one
// step() per period of the plan, then compares the end with the certificate's trial without
// draws. Exit status 0 when the run reaches the goal, held by no verdict, and ends where the
// trial ends; 1 when it does not; 2 for a plan refused or a file that cannot be read.
#include <rbsf/dynamics/io/cell_file.h>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include <rbsf/dynamics/control/sensor_model.h>
#include <rbsf/dynamics/core/simulator.h>
#include <rbsf/executor/plan_runner.h>
#include <rbsf/plan/certificate.h>
#include <rbsf/plan/plan_file.h>
#include <rbsf/plan/plan_reference.h>
#include <rbsf/plan/trial.h>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rbsf_plan_client CELL.yaml PLAN.json\n");
    return 2;
  }
  try {
    rbsf::executor::PlanRunner runner(argv[1]);
    std::string why;
    if (!runner.loadFile(argv[2], &why)) {
      std::fprintf(stderr, "rbsf_plan_client: %s\n", why.c_str());
      return 2;
    }
    const rbsf::RbsfModel& model = runner.model();
    const rbsf::plan::Plan plan = rbsf::plan::readPlanJson(argv[2]).plan;
    const double h = runner.timeStep(), settle = 1.0;
    const rbsf::Simulator sim(model, plan.simulator);
    rbsf::SimulatorWorkspace ws(model.numFingers());
    rbsf::SensorModel sensors(rbsf::plan::lawSensing(model.cell().sensing, plan), h, 0, false);
    rbsf::SimState state(rbsf::plan::nominalDraw(model.cell(), plan).q0,
                         rbsf::VecQ::Zero(plan.q0.size()));
    rbsf::VecU joints(model.controlDim()), tau;
    rbsf::ExecutionStatus status;
    long held = 0;
    runner.start();
    const long ticks = std::lround((plan.duration() + settle) / h);
    for (long k = 0; k < ticks; ++k) {
      sensors.joints(state.q, joints);
      sensors.partPose(k, state.q,
                       [&](double s, const rbsf::Pose& p) { runner.addPartPose(s, p); });
      runner.step(h * static_cast<double>(k), joints, tau, &status);
      held += status.verdict == rbsf::ExecutionVerdict::kHolding;
      sim.step(state, tau, ws);
    }
    std::vector<rbsf::TrajectorySample> trace;
    const rbsf::plan::TrialOutcome o =
        rbsf::plan::traceTrial(model, plan, rbsf::plan::CertificateSettings{}, -1, trace);
    const double to_goal = std::hypot(state.q[0] - plan.goal.x, state.q[1] - plan.goal.y);
    const double to_trial = (state.q - trace.back().q).cwiseAbs().maxCoeff();
    std::printf(
        "rbsf_plan_client: %ld steps of %.0e s: ends %.2g m from the goal and %.2g from the "
        "trial's end (which %s); last verdict %s, %ld ticks held\n",
        ticks, h, to_goal, to_trial, o.success ? "succeeds" : "fails",
        rbsf::toString(status.verdict), held);
    return to_goal <= 0.01 && to_trial < 1e-9 && held == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rbsf_plan_client: %s\n", e.what());
    return 2;
  }
}
