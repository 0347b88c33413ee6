// Cells, poses, the model and its analyses (phase, determinacy, the section-3 conditions,
// holding, placement) for Python.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/state_analysis.h"
#include "rbsf/dynamics/io/cell_file.h"

namespace rbsf::python {

namespace {

/// `v`, refused with "<what> must be finite" when it is not.
double finite(double v, const char* what) {
  if (!std::isfinite(v)) throw InputError(std::string(what) + " must be finite");
  return v;
}

/// A pose from a Pose or any sequence of three numbers.
Pose poseFromSequence(const py::sequence& s) {
  if (py::len(s) != 3)
    throw InputError("pose: expected 3 numbers (x, y, phi), got " + std::to_string(py::len(s)));
  Pose p{s[0].cast<double>(), s[1].cast<double>(), s[2].cast<double>()};
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.phi))
    throw InputError("pose: every entry must be finite");
  return p;
}

void bindCell(py::module_& m) {
  py::class_<FingerParams>(m, "Finger", "One prismatic finger of a cell (read-only).")
      .def_readonly("r", &FingerParams::r, "lateral offset along the base x axis [m]")
      .def_readonly("stroke_min", &FingerParams::stroke_min, "[m]")
      .def_readonly("stroke_max", &FingerParams::stroke_max, "[m]")
      .def_readonly("mass", &FingerParams::mass, "carriage mass [kg]")
      .def_readonly("force_limit", &FingerParams::force_limit, "|tau_i| bound [N]")
      .def("__repr__", [](const FingerParams& f) {
        return "Finger(r=" + std::to_string(f.r) + ", stroke=[" + std::to_string(f.stroke_min) +
               ", " + std::to_string(f.stroke_max) + "])";
      });

  py::class_<Cell>(m, "Cell",
                   "A jig cell: base, fingers, part, friction, sensing and uncertainty "
                   "(docs/model.md \"Files\"). Read-only; build a changed cell from a dict.")
      .def_static("from_file", &loadCell, py::arg("path"),
                  "Read a cell YAML file. Raises ValueError naming the key.")
      .def_static("from_yaml", &parseCell, py::arg("text"), py::arg("label") = "<cell>",
                  "Read a cell from YAML (or JSON) text; `label` names it in messages.")
      .def_readonly("name", &Cell::name)
      .def_readonly("gravity", &Cell::gravity, "g0 [m/s^2]")
      .def_readonly("fingers", &Cell::fingers)
      .def_property_readonly("num_fingers", &Cell::numFingers)
      .def_property_readonly(
          "part_mass", [](const Cell& c) { return c.object.mass; }, "[kg]")
      .def_property_readonly(
          "part_inertia", [](const Cell& c) { return c.object.inertia; }, "about the COM [kg m^2]")
      .def_property_readonly(
          "shape", [](const Cell& c) { return c.object.shape->type(); }, "the part's shape type")
      .def_property_readonly("mu_static", [](const Cell& c) { return c.friction.mu_static; })
      .def_property_readonly("mu_kinetic", [](const Cell& c) { return c.friction.mu_kinetic; })
      .def_property_readonly(
          "theta_limits",
          [](const Cell& c) { return std::make_pair(c.base.theta_min, c.base.theta_max); },
          "the base's angle limits [rad]")
      .def_property_readonly("torque_limit", [](const Cell& c) { return c.base.torque_limit; })
      .def_property_readonly(
          "senses_part", [](const Cell& c) { return c.sensing.part_pose.present; },
          "the cell measures the part's pose (else the joints only)")
      .def("__repr__", [](const Cell& c) {
        return "Cell('" + c.name + "', " + std::to_string(c.numFingers()) + " fingers)";
      });

  py::class_<Pose>(m, "Pose", "A part pose: COM (x, y) [m] in the world and angle phi [rad].")
      .def(py::init([](double x, double y, double phi) {
             return poseFromSequence(py::make_tuple(x, y, phi));
           }),
           py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("phi") = 0.0)
      .def(py::init(&poseFromSequence), py::arg("xyphi"))
      .def_property(
          "x", [](const Pose& p) { return p.x; },
          [](Pose& p, double v) { p.x = finite(v, "pose: x"); }, "[m]")
      .def_property(
          "y", [](const Pose& p) { return p.y; },
          [](Pose& p, double v) { p.y = finite(v, "pose: y"); }, "[m]")
      .def_property(
          "phi", [](const Pose& p) { return p.phi; },
          [](Pose& p, double v) { p.phi = finite(v, "pose: phi"); }, "[rad]")
      .def("__iter__", [](const Pose& p) { return py::iter(py::make_tuple(p.x, p.y, p.phi)); })
      .def("__repr__", [](const Pose& p) {
        return "Pose(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
               std::to_string(p.phi) + ")";
      });
  py::implicitly_convertible<py::tuple, Pose>();
  py::implicitly_convertible<py::list, Pose>();
}

void bindAnalysis(py::module_& m) {
  py::class_<ContactReport>(m, "ContactReport", "One contact of a state's analysis.")
      .def_readonly("xi", &ContactReport::xi, "boundary parameter")
      .def_readonly("gap", &ContactReport::gap, "[m]")
      .def_readonly("normal", &ContactReport::normal, "inward normal n_i (world)")
      .def_readonly("f_n", &ContactReport::f_n, "phase-U normal force (eqs. 21-24) [N]")
      .def_readonly("delta_n", &ContactReport::delta_n, "phase-U normal acceleration [m/s^2]")
      .def_property_readonly("alpha_n", [](const ContactReport& c) { return c.arms.alpha_n; })
      .def_property_readonly(
          "alpha_t", [](const ContactReport& c) { return c.arms.alpha_t; },
          "signed moment arm of the normal about the COM (eq. 25) [m]");

  py::class_<OmegaDotRange>(m, "OmegaDotRange",
                            "The part's angular accelerations reachable with every contact "
                            "closed (paper section 3).")
      .def_readonly("feasible", &OmegaDotRange::feasible)
      .def_readonly("min", &OmegaDotRange::min, "[rad/s^2]")
      .def_readonly("max", &OmegaDotRange::max, "[rad/s^2]")
      .def_readonly("positive", &OmegaDotRange::positive)
      .def_readonly("negative", &OmegaDotRange::negative);

  py::class_<HoldingSolution>(m, "Holding", "Static holding at rest (least-norm forces).")
      .def_readonly("feasible", &HoldingSolution::feasible)
      .def_readonly("tau", &HoldingSolution::tau)
      .def_readonly("f_n", &HoldingSolution::fn)
      .def_readonly("f_t", &HoldingSolution::ft);

  py::class_<StateAnalysis>(m, "StateAnalysis", "Everything the model says about (q, v, tau).")
      .def_readonly("contacts", &StateAnalysis::contacts)
      .def_readonly("accel", &StateAnalysis::accel, "phase-U accelerations (eq. 20)")
      .def_readonly("sigma_min", &StateAnalysis::sigma_min, "smallest singular value of G1")
      .def_readonly("determinate", &StateAnalysis::determinate)
      .def_property_readonly(
          "phase", [](const StateAnalysis& a) { return std::string(toString(a.phase.phase)); })
      .def_readonly("phase_c_feasible", &StateAnalysis::phase_c_feasible)
      .def_readonly("omega_dot", &StateAnalysis::omega_dot)
      .def_readonly("com_regions", &StateAnalysis::com_regions,
                    "contact pairs whose normals enclose the COM (paper Fig. 2)")
      .def_readonly("com_in_end_region", &StateAnalysis::com_in_end_region)
      .def_readonly("holding", &StateAnalysis::holding);
}

void bindModelClass(py::module_& m) {
  py::class_<RbsfModel>(m, "Model",
                        "The model of one cell: kinematics, dynamics and analyses. State "
                        "order (state_layout.h): q = (x, y, phi, theta, l_1..l_m), "
                        "tau = (tau_theta, tau_1..tau_m).")
      .def(py::init<Cell>(), py::arg("cell"))
      .def(py::init([](const std::string& path) { return RbsfModel(loadCell(path)); }),
           py::arg("cell_file"))
      .def_property_readonly("cell", &RbsfModel::cell, py::return_value_policy::copy)
      .def_property_readonly("num_fingers", &RbsfModel::numFingers)
      .def_property_readonly("config_dim", &RbsfModel::configDim, "m + 4")
      .def_property_readonly("control_dim", &RbsfModel::controlDim, "m + 1")
      .def(
          "resting_configuration",
          [](const RbsfModel& model, const Pose& pose, double theta) {
            return toArray(restingConfiguration(model, pose, theta));
          },
          py::arg("pose"), py::arg("theta") = 0.0,
          "q with the part at `pose` and every finger placed under it at base angle theta. "
          "Raises ValueError naming the finger that cannot reach.")
      .def(
          "fingertip",
          [](const RbsfModel& model, const DoubleArray& q, int i) {
            if (i < 0 || i >= model.numFingers())
              throw InputError("finger: must be in 0.." + std::to_string(model.numFingers() - 1));
            return Vec2(model.fingertip(toVector<VecQ>(q, model.configDim(), "q"), i));
          },
          py::arg("q"), py::arg("finger"), "tip p_i in the world [m] (eq. 2)")
      .def(
          "mass_matrix",
          [](const RbsfModel& model, const DoubleArray& q) {
            MatQQ M(model.configDim(), model.configDim());
            model.massMatrix(toVector<VecQ>(q, model.configDim(), "q"), M);
            return Eigen::MatrixXd(M);
          },
          py::arg("q"))
      .def(
          "bias",
          [](const RbsfModel& model, const DoubleArray& q, const DoubleArray& v) {
            VecQ Q(model.configDim());
            model.bias(toVector<VecQ>(q, model.configDim(), "q"),
                       toVector<VecQ>(v, model.configDim(), "v"), Q);
            return toArray(Q);
          },
          py::arg("q"), py::arg("v"), "Q(q, v): gravity, Coriolis and centrifugal terms")
      .def(
          "energy",
          [](const RbsfModel& model, const DoubleArray& q, const DoubleArray& v) {
            const VecQ qq = toVector<VecQ>(q, model.configDim(), "q");
            return model.kineticEnergy(qq, toVector<VecQ>(v, model.configDim(), "v")) +
                   model.potentialEnergy(qq);
          },
          py::arg("q"), py::arg("v"), "kinetic plus potential energy [J]")
      .def(
          "analyze",
          [](const RbsfModel& model, const DoubleArray& q, const DoubleArray& v,
             const DoubleArray& tau) {
            return analyzeState(model, toVector<VecQ>(q, model.configDim(), "q"),
                                toVector<VecQ>(v, model.configDim(), "v"),
                                toVector<VecU>(tau, model.controlDim(), "tau"));
          },
          py::arg("q"), py::arg("v"), py::arg("tau"),
          "The phase (C, P, U), determinacy, the section-3 conditions and static holding of "
          "a state with every finger touching. Raises ValueError naming a finger off the "
          "part.")
      .def("__repr__", [](const RbsfModel& model) { return "Model('" + model.cell().name + "')"; });
}

}  // namespace

void bindModel(py::module_& m) {
  bindCell(m);
  bindAnalysis(m);
  bindModelClass(m);
}

}  // namespace rbsf::python
