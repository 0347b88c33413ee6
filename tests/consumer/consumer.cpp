// Uses the installed rbsf package as a cell controller would: loads a cell into the
// controller facade, plans a short turn (15 degrees, the optimiser tests' seed) on its
// worker thread while this thread polls, and samples the published plan. Also links
// rbsf::trajopt (refines the plan when it can). What is checked is the package, not the
// plan: the facade is asked to publish the plan whatever its certificate, and the exit
// status is 0 when the plan is exact, the facade's samples at the plan's knots equal the
// plan's own q and its control law gives finite inputs there; the certificate's verdict
// is printed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <thread>

#include <rbsf/controller/reorientation_controller.h>
#include <rbsf/dynamics/core/state_layout.h>
#include <rbsf/plan/certificate_report.h>
#include <rbsf/trajopt/plan_optimizer.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: rbsf_consumer CELL.yaml\n");
    return 2;
  }
  try {
    rbsf::controller::ReorientationController ctl(argv[1]);
    rbsf::controller::ReorientationRequest request;
    request.problem.start = {0.1, 0.40, 0.0};
    request.problem.goal = {0.1, 0.40, -15.0 * M_PI / 180.0};
    request.planner.seed = 5;
    request.planner.time_limit = 60.0;
    request.optimize = true;
    request.optimizer.knots = 30;  // small: converges in seconds (as the CLI test's)
    request.optimizer.max_solve_time = 20.0;
    request.certificate.trials = 8;
    request.accept_uncertified = true;
    if (!ctl.plan(request)) return 1;
    long polls = 0;
    while (ctl.status() == rbsf::controller::ControllerStatus::kPlanning) {
      ++polls;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    const rbsf::controller::RequestResult result = ctl.result();
    std::printf("rbsf_consumer: %s after %ld polls%s%s\n", toString(result.outcome), polls,
                result.message.empty() ? "" : ": ", result.message.c_str());
    if (ctl.status() != rbsf::controller::ControllerStatus::kReady) return 1;
    rbsf::ReferenceSample ref;
    const int m = static_cast<int>(result.record.plan.q0.size()) - rbsf::layout::configDim(0);
    rbsf::VecU joints(rbsf::layout::controlDim(m)), tau;
    double worst = 0.0;
    for (const rbsf::plan::PlanSample& s : result.record.plan.samples) {
      if (!ctl.sample(s.t, ref)) return 1;
      worst = std::max(worst, (ref.q - s.q).cwiseAbs().maxCoeff());
      for (int j = 0; j < joints.size(); ++j) joints[j] = s.q[rbsf::layout::inputToConfig(j)];
      if (!ctl.track(s.t, joints, tau) || !tau.allFinite()) return 1;
    }
    std::printf("rbsf_consumer: certificate %s\n",
                rbsf::plan::verdictText(result.record.certificate).c_str());
    const auto& last = result.record.plan.samples.back();
    std::printf(
        "rbsf_consumer: %zu segments, %.3f s, phases %s, final phi %.4f rad (goal "
        "%.4f), largest |q_ref - q| at the knots %.1e\n",
        result.record.plan.segments.size(), result.record.plan.duration(),
        result.record.plan.phaseSequence().c_str(), last.q[rbsf::layout::kPhi],
        request.problem.goal.phi, worst);
    return worst <= 1e-9 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rbsf_consumer: %s\n", e.what());
    return 1;
  }
}
