// The problem, the pipeline's settings with plan-reorientation's defaults, and the
// benchmark problem suites, for Python.
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "rbsf/bench/problem_suite.h"
#include "rbsf/planner/pipeline/reorientation_pipeline.h"

namespace rbsf::python {

namespace {

/// Shares of the friction cone, each in (0, 1] (plan-reorientation's --friction-use rule).
std::vector<double> frictionUses(const std::vector<double>& uses, const std::string& key) {
  for (double use : uses)
    if (!(use > 0.0 && use <= 1.0))
      throw InputError(key + ": each share of the friction cone must be in (0, 1] (got " +
                       std::to_string(use) + ")");
  return uses;
}

std::string methodName(const planner::PipelineSettings& s) {
  switch (s.method) {
    case planner::PipelineMethod::kAuto:
      return "auto";
    case planner::PipelineMethod::kSupport:
      return "support";
    case planner::PipelineMethod::kKinodynamic:
      return planner::toString(s.planner.planner);
  }
  return "auto";
}

void setMethod(planner::PipelineSettings& s, const std::string& name) {
  if (name == "auto") {
    s.method = planner::PipelineMethod::kAuto;
  } else if (name == "support") {
    s.method = planner::PipelineMethod::kSupport;
  } else if (const auto kinodynamic = planner::parsePlanner(name)) {
    s.method = planner::PipelineMethod::kKinodynamic;
    s.planner.planner = *kinodynamic;
  } else {
    throw InputError("method: unknown planner '" + name +
                     "' (choose from auto, support, KPIECE1, RRT, SST, EST, PDST)");
  }
}

}  // namespace

planner::PipelineSettings defaultPlanSettings() {
  planner::PipelineSettings s;
  s.optimize = true;
  return s;
}

void bindPlanSettings(py::module_& m) {
  py::class_<planner::Problem>(m, "Problem", "A reorientation problem: start at rest, goal.")
      .def(py::init([](const Pose& start, const Pose& goal, double start_theta, bool absolute_angle,
                       double position_tolerance, double angle_tolerance) {
             planner::Problem p;
             p.start = start, p.goal = goal, p.start_theta = start_theta;
             p.absolute_angle = absolute_angle;
             p.tolerance.position = position_tolerance, p.tolerance.angle = angle_tolerance;
             planner::checkTolerance(p.tolerance);
             return p;
           }),
           py::arg("start"), py::arg("goal"), py::arg("start_theta") = 0.0,
           py::arg("absolute_angle") = false, py::arg("position_tolerance") = 0.01,
           py::arg("angle_tolerance") = 2.0 * M_PI / 180.0)
      .def_readwrite("start", &planner::Problem::start)
      .def_readwrite("goal", &planner::Problem::goal)
      .def_property(
          "start_theta", [](const planner::Problem& p) { return p.start_theta; },
          [](planner::Problem& p, double v) {
            if (!std::isfinite(v)) throw InputError("start_theta: must be finite");
            p.start_theta = v;
          },
          "the base angle at the start [rad]")
      .def_readwrite("absolute_angle", &planner::Problem::absolute_angle)
      .def_property_readonly("position_tolerance",
                             [](const planner::Problem& p) { return p.tolerance.position; })
      .def_property_readonly("angle_tolerance",
                             [](const planner::Problem& p) { return p.tolerance.angle; });

  py::class_<planner::PipelineSettings>(
      m, "PlanSettings",
      "The pipeline's settings (reorientation_pipeline.h) with plan-reorientation's defaults. "
      "Budgets (max_expansions, max_propagations) give the same plan on any machine where "
      "time_limit does not bind first.")
      .def(py::init(&defaultPlanSettings))
      .def_property("method", &methodName, &setMethod,
                    "auto (support, then KPIECE1), support, or KPIECE1, RRT, SST, EST, PDST")
      .def_property(
          "time_limit", [](const planner::PipelineSettings& s) { return s.planner.time_limit; },
          [](planner::PipelineSettings& s, double v) { s.planner.time_limit = v; },
          "the searches' budget together [s]")
      .def_property(
          "seed", [](const planner::PipelineSettings& s) { return s.planner.seed; },
          [](planner::PipelineSettings& s, std::uint32_t v) { s.planner.seed = v; })
      .def_property(
          "max_propagations",
          [](const planner::PipelineSettings& s) { return s.planner.max_propagations; },
          [](planner::PipelineSettings& s, std::uint64_t v) { s.planner.max_propagations = v; },
          "kinodynamic propagations per search (0: none)")
      .def_property(
          "decisive_modes",
          [](const planner::PipelineSettings& s) { return s.planner.decisive_modes.enabled; },
          [](planner::PipelineSettings& s, bool v) { s.planner.decisive_modes.enabled = v; })
      .def_property(
          "attempts", [](const planner::PipelineSettings& s) { return s.max_attempts; },
          [](planner::PipelineSettings& s, int v) {
            if (v < 0)
              throw InputError("attempts: must be at least 0 (got " + std::to_string(v) + ")");
            s.max_attempts = v;
          },
          "kinodynamic searches at most (0: while the budget lasts)")
      .def_readwrite("optimize", &planner::PipelineSettings::optimize, "refine exact plans")
      .def_property(
          "max_expansions",
          [](const planner::PipelineSettings& s) { return s.support.max_expansions; },
          [](planner::PipelineSettings& s, long v) {
            if (v < 0)
              throw InputError("max_expansions: must be at least 0, 0 for none (got " +
                               std::to_string(v) + ")");
            s.support.max_expansions = v;
          },
          "support planner: expansions over all its searches (0: none)")
      .def_property(
          "friction_uses",
          [](const planner::PipelineSettings& s) { return s.support.friction_uses; },
          [](planner::PipelineSettings& s, const std::vector<double>& v) {
            s.support.friction_uses = frictionUses(v, "friction_uses");
          },
          "support planner: the sticking forces' share of the friction cone, one search per "
          "value in order, each in (0, 1]")
      .def_property(
          "simple_turns",
          [](const planner::PipelineSettings& s) { return s.support.simple_turn_friction_uses; },
          [](planner::PipelineSettings& s, const std::vector<double>& v) {
            s.support.simple_turn_friction_uses = frictionUses(v, "simple_turns");
          },
          "support planner: friction uses of the simple turns searched first")
      .def_property(
          "knots", [](const planner::PipelineSettings& s) { return s.optimizer.knots; },
          [](planner::PipelineSettings& s, int v) { s.optimizer.knots = v; })
      .def_property(
          "optimize_time_limit",
          [](const planner::PipelineSettings& s) { return s.optimizer.max_solve_time; },
          [](planner::PipelineSettings& s, double v) { s.optimizer.max_solve_time = v; })
      .def_property(
          "optimize_iterations",
          [](const planner::PipelineSettings& s) { return s.optimizer.max_iterations; },
          [](planner::PipelineSettings& s, int v) { s.optimizer.max_iterations = v; })
      .def_property(
          "optimize_tolerance",
          [](const planner::PipelineSettings& s) { return s.optimizer.tolerance; },
          [](planner::PipelineSettings& s, double v) { s.optimizer.tolerance = v; })
      .def_readwrite("certificate", &planner::PipelineSettings::certificate);

  py::class_<bench::BenchProblem>(m, "BenchProblem", "One problem of a benchmark suite.")
      .def_readonly("name", &bench::BenchProblem::name)
      .def_readonly("cell_path", &bench::BenchProblem::cell_path)
      .def_readonly("problem", &bench::BenchProblem::problem);
  m.def("load_problem_suite", &bench::loadProblemSuite, py::arg("path"),
        "The problems of a benchmark suite file (tools/bench/problem_suite.h).");
}

}  // namespace rbsf::python
