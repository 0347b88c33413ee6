// The simulator for Python: one step, or a whole rollout of held inputs in C++ with its
// trajectory returned as numpy arrays (no Python call per step).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/simulator.h"
#include "samples.h"

namespace rbsf::python {

namespace {

/// A rollout's trajectory: row k is the state after step k (Samples) and what the step did
/// at the contacts besides their normal forces.
struct Trajectory : Samples {
  py::array_t<double> f_t, slip;
  py::array_t<std::int8_t> mode;        ///< 0 stick, 1 slide, 2 separated
  std::optional<SimState> final_state;  ///< the state after the last step
  double fell_at = -1.0;  ///< time the part fell off the fingers [s], -1 when it did not
};

/// Run `steps[j]` steps of input row j, j = 0, 1, ..., from `start` (file comment).
Trajectory runRollout(const Simulator& sim, const SimState& start, const DoubleArray& tau,
                      const std::vector<long>& steps_in) {
  const RbsfModel& model = sim.model();
  const int m = model.numFingers(), nq = model.configDim(), nu = model.controlDim();
  if (tau.ndim() != 2 || tau.shape(1) != nu)
    throw InputError("tau: expected an array of shape (segments, " + std::to_string(nu) +
                     "), got " + shapeText(tau));
  requireFinite(tau.data(), tau.size(), "tau");
  const py::ssize_t segments = tau.shape(0);
  std::vector<long> steps = steps_in.empty() ? std::vector<long>(segments, 1) : steps_in;
  if (static_cast<py::ssize_t>(steps.size()) != segments)
    throw InputError("steps: expected " + std::to_string(segments) +
                     " counts (one per row of "
                     "tau), got " +
                     std::to_string(steps.size()));
  long total = 0;
  for (std::size_t j = 0; j < steps.size(); ++j) {
    if (steps[j] < 1 || steps[j] > 100000000)
      throw InputError("steps: entry " + std::to_string(j) + " must be in 1..1e8");
    total += steps[j];
  }
  if (total > 100000000) throw InputError("steps: more than 1e8 steps in all");
  if (start.q.size() != nq) throw InputError("state: made for another number of fingers");
  std::vector<VecU> inputs(segments, VecU(nu));
  for (py::ssize_t j = 0; j < segments; ++j)
    for (int k = 0; k < nu; ++k) inputs[j][k] = tau.at(j, k);

  Trajectory out;
  static_cast<Samples&>(out) = allocateSamples(total, m);
  out.f_t = matrix(total, m), out.slip = matrix(total, m);
  out.mode = matrix<std::int8_t>(total, m);
  double *t = out.t.mutable_data(), *q = out.q.mutable_data(), *v = out.v.mutable_data(),
         *u = out.tau.mutable_data(), *fn = out.f_n.mutable_data(), *ft = out.f_t.mutable_data(),
         *slip = out.slip.mutable_data();
  std::int8_t *mode = out.mode.mutable_data(), *phase = out.phase.mutable_data();
  SimState state = start;
  bool diverged = false;
  long taken = 0;
  {
    py::gil_scoped_release release;
    SimulatorWorkspace ws(m);
    HeldInputs held(steps, inputs);
    const VecQ q_start = state.q;
    taken = rollout(sim, state, total, ws, held,
                    [&](const SimState& now, const StepReport& r, const VecU& input, long n) {
                      t[n] = now.t;
                      for (int k = 0; k < nq; ++k)
                        q[n * nq + k] = now.q[k], v[n * nq + k] = now.v[k];
                      for (int k = 0; k < nu; ++k) u[n * nu + k] = input[k];
                      for (int i = 0; i < m; ++i) {
                        fn[n * m + i] = r.contacts[i].f_n, ft[n * m + i] = r.contacts[i].f_t;
                        slip[n * m + i] = r.contacts[i].slip;
                        mode[n * m + i] = static_cast<std::int8_t>(r.contacts[i].mode);
                      }
                      phase[n] = static_cast<std::int8_t>(r.phase);
                      if (!now.q.allFinite() || !now.v.allFinite()) {
                        diverged = true;
                        return false;
                      }
                      if (fellOff(now.q, q_start)) {
                        out.fell_at = now.t;
                        return false;
                      }
                      return true;
                    });
  }
  if (diverged)
    throw std::runtime_error("the simulation diverged at t = " + std::to_string(state.t) + " s");
  if (taken < total) {  // the part fell: keep the steps taken
    for (py::array* a :
         std::initializer_list<py::array*>{&out.t, &out.q, &out.v, &out.tau, &out.f_n, &out.f_t,
                                           &out.slip, &out.mode, &out.phase}) {
      *a = (*a)[py::slice(0, taken, 1)];
    }
  }
  out.final_state = state;
  return out;
}

}  // namespace

void bindSimulator(py::module_& m) {
  py::class_<SimulatorSettings>(m, "SimulatorSettings",
                                "Numerical settings of the simulator (simulator.h).")
      .def(py::init<>())
      .def_readwrite("time_step", &SimulatorSettings::time_step, "h [s]")
      .def_readwrite("activation_distance", &SimulatorSettings::activation_distance)
      .def_readwrite("contact_tolerance", &SimulatorSettings::contact_tolerance)
      .def_readwrite("slip_tolerance", &SimulatorSettings::slip_tolerance)
      .def_readwrite("regularization", &SimulatorSettings::regularization)
      .def_readwrite("curvature_terms", &SimulatorSettings::curvature_terms)
      .def_readwrite("drift_correction", &SimulatorSettings::drift_correction)
      .def_readwrite("max_mode_iterations", &SimulatorSettings::max_mode_iterations);

  py::class_<SimState>(m, "SimState",
                       "Everything a step depends on besides tau: (t, q, v) and the "
                       "contacts' memory. Copy it to resume a run bit for bit.")
      .def(py::init([](const DoubleArray& q, py::object v) {
             const Eigen::Index n = q.ndim() == 1 ? q.shape(0) : -1;
             if (n < 5 || n > kMaxConfig)  // SimState's own check, before the fixed capacity
               throw InputError("q: expected an array of m + 4 numbers (1 <= m <= " +
                                std::to_string(kMaxFingers) + "), got shape " + shapeText(q));
             const VecQ qq = toVector<VecQ>(q, n, "q");
             const VecQ vv =
                 v.is_none() ? VecQ(VecQ::Zero(n)) : toVector<VecQ>(v.cast<DoubleArray>(), n, "v");
             return SimState(qq, vv);
           }),
           py::arg("q"), py::arg("v") = py::none(), "At (q, v); v = 0 (at rest) by default.")
      .def_readonly("t", &SimState::t, "[s]")
      .def_property_readonly("q", [](const SimState& s) { return toArray(s.q); })
      .def_property_readonly("v", [](const SimState& s) { return toArray(s.v); })
      .def_property_readonly(
          "modes",
          [](const SimState& s) {
            std::vector<std::string> out;
            for (Eigen::Index i = 0; i < s.q.size() - 4; ++i) out.emplace_back(toString(s.mode[i]));
            return out;
          },
          "each contact's friction memory: stick, slide or separated")
      .def("copy", [](const SimState& s) { return SimState(s); })
      .def("__copy__", [](const SimState& s) { return SimState(s); })
      .def("__deepcopy__", [](const SimState& s, py::dict) { return SimState(s); });

  py::class_<ContactStepReport>(m, "ContactStep", "What one step did at one contact.")
      .def_property_readonly(
          "mode", [](const ContactStepReport& c) { return std::string(toString(c.mode)); })
      .def_readonly("f_n", &ContactStepReport::f_n, "[N]")
      .def_readonly("f_t", &ContactStepReport::f_t, "[N]")
      .def_readonly("gap", &ContactStepReport::gap, "[m]")
      .def_readonly("slip", &ContactStepReport::slip, "[m/s]");

  py::class_<Trajectory, Samples>(m, "Trajectory",
                                  "A rollout: Samples (row k: the state after step k, the input "
                                  "held over it, f_n, phase) and its contacts' f_t, slip and "
                                  "mode (0 stick, 1 slide, 2 separated).")
      .def_readonly("f_t", &Trajectory::f_t)
      .def_readonly("slip", &Trajectory::slip)
      .def_readonly("mode", &Trajectory::mode)
      .def_readonly("final_state", &Trajectory::final_state)
      .def_readonly("fell_at", &Trajectory::fell_at,
                    "time the part fell off the fingers and the run stopped [s]; -1: never");

  py::class_<Simulator>(m, "Simulator",
                        "The hybrid contact simulator (simulator.h): velocity-level time "
                        "stepping through stick, slip, separation and renewed contact.")
      .def(py::init<const RbsfModel&, const SimulatorSettings&>(), py::arg("model"),
           py::arg("settings") = SimulatorSettings(), py::keep_alive<1, 2>())
      .def_property_readonly("settings", &Simulator::settings, py::return_value_policy::copy,
                             "a copy of its settings (a simulator's settings are fixed)")
      .def(
          "step",
          [](const Simulator& sim, SimState& state, const DoubleArray& tau) {
            const RbsfModel& model = sim.model();
            if (state.q.size() != model.configDim())
              throw InputError("state: made for another number of fingers");
            const VecU u = toVector<VecU>(tau, model.controlDim(), "tau");
            SimulatorWorkspace ws(model.numFingers());
            StepReport report;
            sim.step(state, u, ws, &report);
            std::vector<ContactStepReport> contacts(report.contacts.begin(),
                                                    report.contacts.begin() + model.numFingers());
            return py::make_tuple(contacts, std::string(toString(report.phase)));
          },
          py::arg("state"), py::arg("tau"),
          "Advance `state` (in place) by one step with tau held; returns (contacts, phase).")
      .def(
          "rollout",
          [](const Simulator& sim, py::object start, const DoubleArray& tau,
             const std::vector<long>& steps) {
            if (py::isinstance<SimState>(start))
              return runRollout(sim, start.cast<const SimState&>(), tau, steps);
            const int nq = sim.model().configDim();
            return runRollout(
                sim,
                SimState(toVector<VecQ>(start.cast<DoubleArray>(), nq, "start"), VecQ::Zero(nq)),
                tau, steps);
          },
          py::arg("start"), py::arg("tau"), py::arg("steps") = std::vector<long>{},
          "From `start` (a SimState, or q at rest), hold row j of tau (segments x (m + 1)) "
          "for steps[j] steps (default 1 each), all in C++ without the GIL; stops when the "
          "part falls off. Returns a Trajectory; `start` is not changed.");
}

}  // namespace rbsf::python
