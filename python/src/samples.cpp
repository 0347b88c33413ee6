#include "samples.h"

namespace rbsf::python {

Samples allocateSamples(py::ssize_t n, int m) {
  return Samples{py::array_t<double>(n), matrix(n, m + 4), matrix(n, m + 4),
                 matrix(n, m + 1),       matrix(n, m),     py::array_t<std::int8_t>(n)};
}

Samples samplesOf(const std::vector<TrajectorySample>& in, int m) {
  const auto n = static_cast<py::ssize_t>(in.size());
  const py::ssize_t nq = m + 4, nu = m + 1;
  Samples s = allocateSamples(n, m);
  double *t = s.t.mutable_data(), *q = s.q.mutable_data(), *v = s.v.mutable_data(),
         *u = s.tau.mutable_data(), *f = s.f_n.mutable_data();
  std::int8_t* ph = s.phase.mutable_data();
  for (py::ssize_t k = 0; k < n; ++k) {
    const TrajectorySample& x = in[static_cast<std::size_t>(k)];
    t[k] = x.t, ph[k] = static_cast<std::int8_t>(x.phase);
    for (py::ssize_t i = 0; i < nq; ++i) q[k * nq + i] = x.q[i], v[k * nq + i] = x.v[i];
    for (py::ssize_t i = 0; i < nu; ++i) u[k * nu + i] = x.tau[i];
    for (py::ssize_t i = 0; i < m; ++i) f[k * m + i] = i < x.f_n.size() ? x.f_n[i] : 0.0;
  }
  return s;
}

void bindSamples(py::module_& m) {
  py::class_<Samples>(m, "Samples",
                      "Sampled states as arrays: t (N), q and v (N, m + 4), tau (N, m + 1, "
                      "held over the step ending there), f_n (N, m), phase (N: 0 C, 1 P, 2 U, "
                      "3 unsupported).")
      .def_readonly("t", &Samples::t)
      .def_readonly("q", &Samples::q)
      .def_readonly("v", &Samples::v)
      .def_readonly("tau", &Samples::tau)
      .def_readonly("f_n", &Samples::f_n)
      .def_readonly("phase", &Samples::phase)
      .def("__len__", [](const Samples& s) { return s.t.shape(0); });
}

}  // namespace rbsf::python
