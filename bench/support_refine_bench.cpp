// scratch
#include <cstdio>
#include <string>
#include <vector>
#include "rbsf/dynamics/cell.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan.h"
#include "rbsf/tools/tool_main.h"
#include "rbsf/trajopt/plan_optimizer.h"

namespace {
int run(int argc, char** argv) {
  std::vector<std::string> files;
  rbsf::trajopt::OptimizerSettings os;
  int trials = 64;
  double dmin = 1.0, dmax = 1.0;
  std::string out;
  CLI::App app{"scratch", "support_refine"};
  app.add_option("files", files)->required();
  app.add_option("--cone", os.cone_margin);
  os.stated_roles = true;
  app.add_option("--knots", os.knots);
  app.add_option("--trials", trials);
  app.add_option("--dmin", dmin);
  app.add_option("--dmax", dmax);
  app.add_option("--slide-dmin", os.slide_duration_min_scale);
  app.add_option("--slip", os.min_slip_rate);
  app.add_option("--floor", os.normal_floor);
  app.add_option("--tube", os.tube_position);
  app.add_option("--tube-angle", os.tube_angle);
  app.add_option("--smooth", os.smoothness_weight);
  app.add_option("--out", out);
  app.add_option("--print", os.print_level);
  rbsf::tools::parseCommandLine(app, argc, argv);
  os.duration_min_scale = dmin;
  os.duration_max_scale = dmax;
  const rbsf::RbsfModel model(rbsf::loadCell(RBSF_SOURCE_DIR "/cells/default.yaml"));
  const rbsf::trajopt::PlanOptimizer opt(model, os);
  rbsf::plan::CertificateSettings cs;
  cs.trials = trials;
  for (const std::string& f : files) {
    rbsf::plan::Plan p = rbsf::plan::readPlanJson(f);
    rbsf::trajopt::OptimizedPlan o = opt.optimize(p);
    const auto& s = o.plan.optimization;
    std::printf("%s: %s %d it %.3f s effort %.4f -> %.4f\n", f.c_str(), s.status.c_str(),
                s.iterations, s.solve_time, s.cost_before, s.cost_after);
    if (!o.success) continue;
    std::vector<rbsf::plan::TrialOutcome> outs;
    const auto c0 = rbsf::plan::certify(model, p, cs);
    const auto c = rbsf::plan::certify(model, o.plan, cs, &outs);
    std::printf("  planner %d/%d, refined %d/%d (bound %.3f)\n", c0.successes, c0.trials,
                c.successes, c.trials, c.lower_bound);
    for (int i = 0, shown = 0; shown < 3 && i < (int)outs.size(); ++i)
      if (!outs[i].success && ++shown) std::printf("   trial %d: %s\n", i, outs[i].failure.c_str());
    if (!out.empty()) rbsf::plan::writePlanJson(o.plan, out);
    std::vector<rbsf::TrajectorySample> tr;
    const auto nom = rbsf::plan::traceTrial(model, o.plan, cs, 0, tr);
    std::printf("  nominal: %s\n", nom.failure.c_str());
    double next = 0;
    for (const auto& x : tr) {
      const bool sat =
          x.tau.cwiseAbs().maxCoeff() > 0.97 * 800.0 || std::abs(x.tau[0]) > 0.97 * 400.0;
      if (x.t < next && !sat) continue;
      if (!sat) next += 0.25;
      if (x.t > 0) break;
      const rbsf::plan::PlanSample* r = &o.plan.samples[0];
      for (const auto& y : o.plan.samples)
        if (y.t <= x.t) r = &y;
      std::printf("  t %.2f q", x.t);
      for (int i = 0; i < x.q.size(); ++i) std::printf(" %+.4f", x.q[i]);
      std::printf(" | ref");
      for (int i = 0; i < x.q.size(); ++i) std::printf(" %+.4f", r->q[i]);
      std::printf(" | tau");
      for (int i = 0; i < x.tau.size(); ++i) std::printf(" %+.1f/%+.1f", x.tau[i], r->tau[i]);
      std::printf(" | fn");
      for (int i = 0; i < x.f_n.size(); ++i) std::printf(" %.1f/%.1f", x.f_n[i], r->f_n[i]);
      std::printf("\n");
    }
  }
  return 0;
}
}  // namespace
int main(int argc, char** argv) { return rbsf::tools::toolMain("support_refine", argc, argv, run); }
