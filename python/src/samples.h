#pragma once
/// \file
/// \brief Sampled states as numpy arrays (row k is sample k): a plan's samples, a trial's
///        trace, and the part of a rollout's trajectory they share.

#include <vector>

#include "arrays.h"
#include "rbsf/dynamics/core/trajectory_sample.h"

namespace rbsf::python {

/// \brief t (N), q and v (N, m + 4), tau (N, m + 1), f_n (N, m), phase (N: 0 C, 1 P, 2 U,
///        3 unsupported).
struct Samples {
  py::array_t<double> t, q, v, tau, f_n;
  py::array_t<std::int8_t> phase;
};

/// \brief The arrays of `n` samples of a cell with `m` fingers, not filled.
Samples allocateSamples(py::ssize_t n, int m);

/// \brief `in` (a plan's samples, a trace) as arrays.
Samples samplesOf(const std::vector<TrajectorySample>& in, int m);

/// \brief The class Samples.
void bindSamples(py::module_& m);

}  // namespace rbsf::python
