// The Python module rbsf._rbsf (docs/python.md); the package rbsf re-exports it.
#include "bindings.h"
#include "rbsf/dynamics/core/errors.h"
#include "samples.h"

PYBIND11_MODULE(_rbsf, m) {
  m.doc() = "rbsf: planning, simulation and execution for the RBSF jig (docs/python.md)";
  m.attr("__version__") = RBSF_VERSION;  // the CMake project's version
  // Bad input (a cell key, an array's shape, a plan file) is a ValueError with the
  // library's message; other failures stay RuntimeError.
  pybind11::register_exception<rbsf::InputError>(m, "InputError", PyExc_ValueError);
  rbsf::python::bindModel(m);
  rbsf::python::bindSamples(m);
  rbsf::python::bindSimulator(m);
  rbsf::python::bindPlans(m);
  rbsf::python::bindPlanSettings(m);
  rbsf::python::bindPipeline(m);
  rbsf::python::bindController(m);
}
