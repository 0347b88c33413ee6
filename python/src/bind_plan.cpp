// Plans as numpy arrays, plan files, certificates and single trials (replays, draws).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/plan_file.h"
#include "rbsf/plan/trial.h"
#include "samples.h"

namespace rbsf::python {

namespace {

int fingersOf(const plan::Plan& p) { return static_cast<int>(p.q0.size()) - 4; }

/// The roles of the segment each sample's step belongs to (a sample at a segment's end is
/// that segment's).
std::vector<std::string> sampleRoles(const plan::Plan& p) {
  std::vector<std::string> out;
  out.reserve(p.samples.size());
  if (p.segments.empty()) return std::vector<std::string>(p.samples.size());
  std::size_t j = 0;
  double end = p.segments[0].duration;
  for (const TrajectorySample& x : p.samples) {
    while (j + 1 < p.segments.size() && x.t > end + 1e-9) end += p.segments[++j].duration;
    out.push_back(rolesText(p.segments[j].contacts, fingersOf(p)));
  }
  return out;
}

void bindPlanClasses(py::module_& m) {
  py::class_<plan::PlanSegment>(m, "PlanSegment", "tau held (or ramped) over whole steps.")
      .def_property_readonly(
          "phase", [](const plan::PlanSegment& s) { return std::string(toString(s.phase)); })
      .def_readonly("steps", &plan::PlanSegment::steps)
      .def_readonly("duration", &plan::PlanSegment::duration, "[s]")
      .def_property_readonly("tau", [](const plan::PlanSegment& s) { return toArray(s.tau); })
      .def_property_readonly(
          "tau_end",
          [](const plan::PlanSegment& s) -> py::object {
            if (s.tau_end.size() == 0) return py::none();
            return toArray(s.tau_end);
          },
          "None: tau held; else tau ramps linearly to it")
      .def_property_readonly(
          "roles",
          [](const plan::PlanSegment& s) {
            return rolesText(s.contacts, static_cast<int>(s.tau.size()) - 1);
          },
          "each finger's role: S stick, + / - slide, L lifted, F free");

  py::class_<plan::Plan>(m, "Plan", "A plan: tau segments and the trajectory they produce.")
      .def_property_readonly(
          "status", [](const plan::Plan& p) { return std::string(plan::toString(p.status)); })
      .def_readonly("planner", &plan::Plan::planner)
      .def_readonly("seed", &plan::Plan::seed)
      .def_readonly("goal_distance", &plan::Plan::goal_distance, "[tolerance units]")
      .def_readonly("start", &plan::Plan::start)
      .def_readonly("goal", &plan::Plan::goal)
      .def_readonly("start_theta", &plan::Plan::start_theta)
      .def_readonly("joint_feedback", &plan::Plan::joint_feedback,
                    "held by the joints alone: its law feeds back the joints only")
      .def_property_readonly("time_step", [](const plan::Plan& p) { return p.simulator.time_step; })
      .def_property_readonly("q0", [](const plan::Plan& p) { return toArray(p.q0); })
      .def_property_readonly("duration", &plan::Plan::duration, "[s]")
      .def_property_readonly("phase_sequence", &plan::Plan::phaseSequence)
      .def_property_readonly("planned_phases", &plan::Plan::plannedPhases)
      .def_property_readonly("pivots", &plan::Plan::pivots)
      .def_readonly("segments", &plan::Plan::segments)
      .def_property_readonly(
          "segment_starts",
          [](const plan::Plan& p) {
            py::array_t<double> out(static_cast<py::ssize_t>(p.segments.size()));
            double t = 0.0;
            for (std::size_t j = 0; j < p.segments.size(); ++j)
              out.mutable_data()[j] = t, t += p.segments[j].duration;
            return out;
          },
          "each segment's start time [s]")
      .def_property_readonly("samples",
                             [](const plan::Plan& p) { return samplesOf(p.samples, fingersOf(p)); })
      .def_property_readonly("sample_roles", &sampleRoles,
                             "each sample's planned contact roles (its segment's): S stick, "
                             "+ / - slide, L lifted, F free")
      .def("__repr__", [](const plan::Plan& p) {
        return "Plan(" + std::string(plan::toString(p.status)) + ", " + p.plannedPhases() + ", " +
               std::to_string(p.duration()) + " s)";
      });
}

void bindCertificate(py::module_& m) {
  py::class_<plan::TrialOutcome>(m, "TrialOutcome", "How one closed-loop trial ended.")
      .def_readonly("index", &plan::TrialOutcome::index)
      .def_readonly("success", &plan::TrialOutcome::success)
      .def_readonly("failure", &plan::TrialOutcome::failure)
      .def_readonly("position_error", &plan::TrialOutcome::position_error, "[m]")
      .def_readonly("angle_error", &plan::TrialOutcome::angle_error, "[rad]")
      .def_readonly("dropped", &plan::TrialOutcome::dropped)
      .def_readonly("dropped_time", &plan::TrialOutcome::dropped_time)
      .def_readonly("max_deviation", &plan::TrialOutcome::max_deviation)
      .def_readonly("phases", &plan::TrialOutcome::phases)
      .def_property_readonly(
          "end",
          [](const plan::TrialOutcome& o) { return std::string(toString(plan::trialEnd(o))); },
          "done, held, lost or off");

  py::class_<plan::Certificate>(m, "Certificate",
                                "Evidence that a plan runs: closed-loop trials under the "
                                "cell's sensing and uncertainty, judged by outcome.")
      .def_readonly("ran", &plan::Certificate::ran)
      .def_readonly("certified", &plan::Certificate::certified)
      .def_property_readonly(
          "law", [](const plan::Certificate& c) { return std::string(toString(c.law)); })
      .def_readonly("trials", &plan::Certificate::trials)
      .def_readonly("successes", &plan::Certificate::successes)
      .def_readonly("success_rate", &plan::Certificate::success_rate)
      .def_readonly("lower_bound", &plan::Certificate::lower_bound)
      .def_readonly("confidence", &plan::Certificate::confidence)
      .def_readonly("required_rate", &plan::Certificate::required_rate)
      .def_readonly("seed", &plan::Certificate::seed)
      .def_readonly("worst", &plan::Certificate::worst)
      .def_property_readonly("verdict", &plan::verdictText, "one line")
      .def_property_readonly("report", &plan::certificateReportText, "the tools' report")
      .def("__repr__", [](const plan::Certificate& c) {
        return c.ran ? "Certificate(" + plan::verdictText(c) + ")"
                     : std::string("Certificate(not run)");
      });

  py::class_<plan::CertificateSettings>(m, "CertificateSettings",
                                        "How a certificate is made (certificate.h).")
      .def(py::init<>())
      .def_readwrite("trials", &plan::CertificateSettings::trials, "a fixed count; 0: sequential")
      .def_readwrite("batch", &plan::CertificateSettings::batch)
      .def_readwrite("max_trials", &plan::CertificateSettings::max_trials)
      .def_readwrite("confidence", &plan::CertificateSettings::confidence)
      .def_readwrite("required_rate", &plan::CertificateSettings::required_rate)
      .def_readwrite("seed", &plan::CertificateSettings::seed)
      .def_readwrite("threads", &plan::CertificateSettings::threads, "0: one per core")
      .def_readwrite("open_loop", &plan::CertificateSettings::open_loop);

  py::class_<plan::OptimizationSummary>(m, "OptimizationSummary", "How a refinement went.")
      .def_readonly("ran", &plan::OptimizationSummary::ran)
      .def_readonly("iterations", &plan::OptimizationSummary::iterations)
      .def_readonly("cost_before", &plan::OptimizationSummary::cost_before)
      .def_readonly("cost_after", &plan::OptimizationSummary::cost_after)
      .def_readonly("chosen", &plan::OptimizationSummary::chosen)
      .def_readonly("message", &plan::OptimizationSummary::message);

  py::class_<plan::PlanRecord>(m, "PlanRecord",
                               "A plan with its certificate and optimisation summary: what a "
                               "plan file holds.")
      .def_readonly("plan", &plan::PlanRecord::plan)
      .def_readonly("certificate", &plan::PlanRecord::certificate)
      .def_readonly("optimization", &plan::PlanRecord::optimization)
      .def_static("read", &plan::readPlanJson, py::arg("path"),
                  "Read a plan file. Raises ValueError naming the file and key.")
      .def_static(
          "from_json", [](const std::string& text) { return plan::parsePlanJson(text, "<json>"); },
          py::arg("text"))
      .def(
          "to_json",
          [](const plan::PlanRecord& r, bool reproducible) {
            return plan::planJsonText(r, plan::PlanFileOptions{!reproducible});
          },
          py::arg("reproducible") = false,
          "The plan file's text; reproducible leaves the wall-clock fields out.")
      .def(
          "write",
          [](const plan::PlanRecord& r, const std::string& path, bool reproducible) {
            plan::writePlanJson(r, path, plan::PlanFileOptions{!reproducible});
          },
          py::arg("path"), py::arg("reproducible") = false,
          "Write the plan file atomically (complete or absent).");
}

void bindTrials(py::module_& m) {
  m.def(
      "certify",
      [](const RbsfModel& model, const plan::Plan& p, const plan::CertificateSettings& settings) {
        py::gil_scoped_release release;
        return plan::certify(model, p, settings);
      },
      py::arg("model"), py::arg("plan"), py::arg("settings") = plan::CertificateSettings(),
      "Certify `plan` on the model's cell: closed-loop trials on every core (the GIL "
      "released); the same seed gives the same certificate.");
  m.def(
      "replay_trial",
      [](const RbsfModel& model, const plan::Plan& p, int index,
         const plan::CertificateSettings& settings) {
        std::vector<TrajectorySample> trace;
        plan::TrialOutcome outcome;
        {
          py::gil_scoped_release release;
          outcome = plan::traceTrial(model, p, settings, index, trace);
        }
        return py::make_tuple(outcome, samplesOf(trace, model.numFingers()));
      },
      py::arg("model"), py::arg("plan"), py::arg("index"),
      py::arg("settings") = plan::CertificateSettings(),
      "Trial `index` of a certificate again (-1: the nominal trial): (outcome, every step's "
      "true state as Samples).");
  m.def(
      "draw_trial",
      [](const RbsfModel& model, const plan::Plan& p, std::uint64_t seed, int index) {
        if (p.q0.size() != model.configDim())
          throw InputError("the plan is for " + std::to_string(p.q0.size() - 4) +
                           " fingers, the cell has " + std::to_string(model.numFingers()));
        const plan::TrialDraw d = plan::drawTrial(model.cell(), p, seed, index);
        py::dict out;
        out["part_mass"] = d.cell.object.mass;
        out["part_inertia"] = d.cell.object.inertia;
        out["mu_static"] = d.cell.friction.mu_static;
        out["mu_kinetic"] = d.cell.friction.mu_kinetic;
        out["com_offset"] = Eigen::Vector2d(d.com_offset);
        out["q0"] = toArray(d.q0);
        out["actuator_gain"] = toArray(d.actuator_gain);
        return out;
      },
      py::arg("model"), py::arg("plan"), py::arg("seed"), py::arg("index"),
      "The plant, start and actuators trial `index` of `seed` draws on the model's cell "
      "(trial.h), as a dict.");
}

}  // namespace

void bindPlans(py::module_& m) {
  bindPlanClasses(m);
  bindCertificate(m);
  bindTrials(m);
}

}  // namespace rbsf::python
