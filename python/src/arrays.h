#pragma once
/// \file
/// \brief numpy arrays in and out of the library's fixed-capacity Eigen vectors: every
///        array that comes in is checked for its shape and for finite entries, and refused
///        with an InputError (ValueError in Python) naming the argument, so a bad array can
///        never overrun a fixed capacity or put a NaN into the physics.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf::python {

namespace py = pybind11;

/// \brief A float64 array view of any array-like (numpy converts lists and other dtypes).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// \brief The shape of an array as text, "(3,)" or "(10, 4)".
std::string shapeText(const py::array& a);

/// \brief Throws InputError "<name>: entry <i> is not finite" for the first NaN or infinity
///        among the `n` doubles at `data`.
void requireFinite(const double* data, py::ssize_t n, const std::string& name);

/// \brief A 1-D array of exactly `size` finite entries copied into a fixed-capacity vector.
/// \throws InputError naming `name` for another shape or a non-finite entry.
template <class Vec>
Vec toVector(const DoubleArray& a, Eigen::Index size, const std::string& name) {
  if (a.ndim() != 1 || a.shape(0) != size)
    throw InputError(name + ": expected an array of " + std::to_string(size) +
                     " numbers, got shape " + shapeText(a));
  requireFinite(a.data(), a.size(), name);
  Vec v(size);
  for (Eigen::Index i = 0; i < size; ++i) v[i] = a.data()[i];
  return v;
}

/// \brief Copy a vector into a new 1-D numpy array.
template <class Vec>
py::array_t<double> toArray(const Vec& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  double* p = out.mutable_data();
  for (Eigen::Index i = 0; i < v.size(); ++i) p[i] = v[i];
  return out;
}

/// \brief A 2-D array (rows, cols), filled by the caller.
template <class T = double>
py::array_t<T> matrix(py::ssize_t rows, py::ssize_t cols) {
  return py::array_t<T>({rows, cols});
}

}  // namespace rbsf::python
