// A client of rbsf::plan and rbsf::dynamics alone: reads a cell and a plan file, checks
// that the plan was made for this cell (plan::planCellMismatch) and runs the certificate's
// trial without draws (the plan's law, exact sensors, the nominal plant at 1 kHz). Exit
// status 0 when that trial reaches the goal; 1 when it does not; 2 for a plan of another
// cell or a file that cannot be read.
#include <rbsf/dynamics/io/cell_file.h>
#include <cstdio>
#include <exception>
#include <vector>

#include <rbsf/dynamics/core/cell.h>
#include <rbsf/dynamics/core/model.h>
#include <rbsf/plan/certificate.h>
#include <rbsf/plan/plan_file.h>
#include <rbsf/plan/plan_fit.h>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rbsf_plan_client CELL.yaml PLAN.json\n");
    return 2;
  }
  try {
    const rbsf::RbsfModel model(rbsf::loadCell(argv[1]));
    const rbsf::plan::Plan plan = rbsf::plan::readPlanJson(argv[2]).plan;
    const std::string mismatch = rbsf::plan::planCellMismatch(model, plan);
    if (!mismatch.empty()) {
      std::fprintf(stderr, "rbsf_plan_client: %s\n", mismatch.c_str());
      return 2;
    }
    std::vector<rbsf::TrajectorySample> trace;
    const rbsf::plan::TrialOutcome o =
        rbsf::plan::traceTrial(model, plan, rbsf::plan::CertificateSettings{}, -1, trace);
    std::printf(
        "rbsf_plan_client: nominal trial %s over %zu steps: ends %.2g m and %.2g deg "
        "from the goal%s%s\n",
        o.success ? "succeeds" : "fails", trace.size(), o.position_error,
        o.angle_error * 180.0 / 3.141592653589793, o.success ? "" : ": ", o.failure.c_str());
    return o.success ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rbsf_plan_client: %s\n", e.what());
    return 2;
  }
}
