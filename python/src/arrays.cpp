#include "arrays.h"

#include <cmath>

namespace rbsf::python {

std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

void requireFinite(const double* data, py::ssize_t n, const std::string& name) {
  for (py::ssize_t i = 0; i < n; ++i)
    if (!std::isfinite(data[i]))
      throw InputError(name + ": entry " + std::to_string(i) + " is not finite");
}

}  // namespace rbsf::python
