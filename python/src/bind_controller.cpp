// The controller facade for Python: load a plan, then track() from a control loop (a
// Python plant, a MuJoCo model, a rig), with the execution status every tick.
#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "rbsf/controller/reorientation_controller.h"

namespace rbsf::python {

namespace {

using controller::ReorientationController;

/// Refusals of load() and loadFile() become ValueError with the controller's reason.
void loaded(bool ok, const std::string& why) {
  if (!ok) throw InputError(why.empty() ? std::string("the plan was refused") : why);
}

std::string bitsText(std::uint32_t bits, int m) {
  std::string s;
  for (int i = 0; i < m; ++i)
    if (bits & (1u << i)) s += (s.empty() ? "" : ",") + std::to_string(i + 1);
  return s;
}

void bindStatus(py::module_& m) {
  py::class_<ExecutionStatus>(m, "ExecutionStatus",
                              "One tick's execution status (execution_status.h); track() fills "
                              "it in place.")
      .def(py::init<>())
      .def_readonly("plan_time", &ExecutionStatus::plan_time, "[s]")
      .def_readonly("position_deviation", &ExecutionStatus::position_deviation, "[m]")
      .def_readonly("angle_deviation", &ExecutionStatus::angle_deviation, "[deg]")
      .def_readonly("stroke_deviation", &ExecutionStatus::stroke_deviation, "[m]")
      .def_readonly("stroke_speed_deviation", &ExecutionStatus::stroke_speed_deviation, "[m/s]")
      .def_readonly("saturated", &ExecutionStatus::saturated)
      .def_readonly("pose_seen", &ExecutionStatus::pose_seen)
      .def_readonly("pose_age", &ExecutionStatus::pose_age, "[s]")
      .def_readonly("bad_readings", &ExecutionStatus::bad_readings)
      .def_readonly("flags", &ExecutionStatus::flags, "ExecutionFlag bits")
      .def_property_readonly("flags_text",
                             [](const ExecutionStatus& s) { return flagsText(s.flags); })
      .def_property_readonly(
          "contact_open",
          [](const ExecutionStatus& s) { return bitsText(s.contact_open, kMaxFingers); },
          "relied-on contacts open, fingers counted from 1")
      .def_property_readonly(
          "verdict", [](const ExecutionStatus& s) { return std::string(toString(s.verdict)); },
          "on plan, degraded, leaving, holding or done")
      .def_property_readonly(
          "hold_reason",
          [](const ExecutionStatus& s) { return std::string(toString(s.hold_reason)); })
      .def_readonly("hold_time", &ExecutionStatus::hold_time, "[s]")
      .def("__repr__", [](const ExecutionStatus& s) {
        return "ExecutionStatus(" + std::string(toString(s.verdict)) +
               ", t=" + std::to_string(s.plan_time) + ")";
      });
}

void bindFacade(py::module_& m) {
  py::class_<ReorientationController>(
      m, "Controller",
      "The cell controller's facade (reorientation_controller.h): publish a certified plan, "
      "then call track() once per control period with the joints measured.")
      .def(py::init<const std::string&>(), py::arg("cell_file"))
      .def(py::init<Cell>(), py::arg("cell"))
      .def(
          "load_file",
          [](ReorientationController& c, const std::string& path, bool accept_uncertified,
             bool accept_other_evidence) {
            std::string why;
            loaded(c.loadFile(path, &why,
                              executor::LoadOptions{accept_uncertified, accept_other_evidence}),
                   why);
          },
          py::arg("path"), py::arg("accept_uncertified") = false,
          py::arg("accept_other_evidence") = false,
          "Publish a plan file. Raises ValueError with the reason when it is refused (another "
          "cell, no or a failed certificate, another cell's evidence).")
      .def(
          "load",
          [](ReorientationController& c, const plan::PlanRecord& record, bool accept_uncertified,
             bool accept_other_evidence) {
            std::string why;
            loaded(c.load(record, &why,
                          executor::LoadOptions{accept_uncertified, accept_other_evidence}),
                   why);
          },
          py::arg("record"), py::arg("accept_uncertified") = false,
          py::arg("accept_other_evidence") = false, "Publish a PlanRecord, as load_file().")
      .def(
          "track",
          [](ReorientationController& c, double t, const DoubleArray& joints, py::object out,
             py::object status) -> py::object {
            const int nu = c.model().controlDim();
            if (joints.ndim() != 1 || joints.shape(0) != nu)
              throw InputError("joints: expected an array of " + std::to_string(nu) +
                               " numbers (theta, l_1..l_m), got shape " + shapeText(joints));
            VecU measured(nu), tau(nu);
            for (int k = 0; k < nu; ++k)
              measured[k] = joints.data()[k];  // NaN: the guard bridges it
            if (!status.is_none() && !py::isinstance<ExecutionStatus>(status))
              throw InputError("status: expected an rbsf.ExecutionStatus");
            // `out` is written in place: only a contiguous float64 array of the right size
            // (a conversion would write into a copy the caller never sees).
            double* target = nullptr;
            if (!out.is_none()) {
              const py::array a =
                  py::isinstance<py::array>(out) ? out.cast<py::array>() : py::array();
              if (!a || !a.dtype().is(py::dtype::of<double>()) || a.ndim() != 1 ||
                  a.shape(0) != nu || !a.writeable() || !(a.flags() & py::array::c_style))
                throw InputError("out: expected a writeable, contiguous float64 array of " +
                                 std::to_string(nu) + " numbers");
              target = static_cast<double*>(out.cast<py::array>().mutable_data());
            }
            const bool ok = status.is_none()
                                ? c.track(t, measured, tau)
                                : c.track(t, measured, tau, status.cast<ExecutionStatus&>());
            if (!ok) throw std::runtime_error("track: no plan is published");
            if (target == nullptr) return toArray(tau);
            for (int k = 0; k < nu; ++k) target[k] = tau[k];
            return out;
          },
          py::arg("t"), py::arg("joints"), py::arg("out") = py::none(),
          py::arg("status") = py::none(),
          "The input tau (tau_theta, tau_1..tau_m) for the period [t, t + h) from the joints "
          "measured at t, by the published plan's law; written into `out` when given, and the "
          "tick's status into `status` (an ExecutionStatus). Non-finite joints are bridged, "
          "then held.")
      .def(
          "track_log",
          [](ReorientationController& c, const DoubleArray& times, const DoubleArray& joints) {
            const int nu = c.model().controlDim();
            if (times.ndim() != 1 || joints.ndim() != 2 || joints.shape(0) != times.shape(0) ||
                joints.shape(1) != nu)
              throw InputError("track_log: expected times (N,) and joints (N, " +
                               std::to_string(nu) + "), got " + shapeText(times) + " and " +
                               shapeText(joints));
            const py::ssize_t n = times.shape(0);
            py::array_t<double> taus = matrix(n, nu);
            py::array_t<std::int8_t> verdicts(n);
            double* out = taus.mutable_data();
            std::int8_t* verdict = verdicts.mutable_data();
            {
              py::gil_scoped_release release;
              VecU measured(nu), tau(nu);
              ExecutionStatus status;
              for (py::ssize_t k = 0; k < n; ++k) {
                for (int j = 0; j < nu; ++j) measured[j] = joints.data()[k * nu + j];
                if (!c.track(times.data()[k], measured, tau, status))
                  throw std::runtime_error("track_log: no plan is published");
                for (int j = 0; j < nu; ++j) out[k * nu + j] = tau[j];
                verdict[k] = static_cast<std::int8_t>(status.verdict);
              }
            }
            return py::make_tuple(taus, verdicts);
          },
          py::arg("times"), py::arg("joints"),
          "track() over a log of readings in C++ (a recorded run replayed through the law): "
          "(tau (N, m + 1), verdict codes (N): 0 on plan, 1 degraded, 2 leaving, 3 holding, "
          "4 done).")
      .def(
          "add_part_pose",
          [](ReorientationController& c, double stamp, const Pose& pose) {
            c.addPartPose(stamp, pose);
          },
          py::arg("stamp"), py::arg("pose"), "A part pose measured at plan time `stamp`.")
      .def("start", &ReorientationController::start, "The next track() starts the plan afresh.")
      .def("hold", &ReorientationController::hold,
           "Bring the reference to rest on the plan's path.")
      .def(
          "held_state",
          [](const ReorientationController& c) -> py::object {
            Pose part;
            double theta = 0.0;
            if (!c.heldState(part, theta)) return py::none();
            return py::make_tuple(part, theta);
          },
          "(pose, theta) where the held part is estimated; None when not holding")
      .def_property_readonly("time_step", &ReorientationController::timeStep,
                             "the control period [s]")
      .def_property_readonly("plan_id", &ReorientationController::planId)
      .def(
          "sample",
          [](const ReorientationController& c, double t) -> py::object {
            ReferenceSample s;
            if (!c.sample(t, s)) return py::none();
            py::dict d;
            d["t"] = s.t, d["q"] = toArray(s.q), d["v"] = toArray(s.v), d["tau"] = toArray(s.tau);
            d["phase"] = std::string(toString(s.phase));
            d["roles"] = rolesText(s.roles, c.model().numFingers());
            return d;
          },
          py::arg("t"), "The published plan's reference at t (a dict), None when none")
      .def_property_readonly(
          "duration",
          [](const ReorientationController& c) -> py::object {
            double duration = 0.0;
            VecQ q0;
            if (!c.publishedPlan(duration, q0)) return py::none();
            return py::float_(duration);
          },
          "the published plan's duration [s]; None when none");
}

}  // namespace

void bindController(py::module_& m) {
  bindStatus(m);
  bindFacade(m);
}

}  // namespace rbsf::python
