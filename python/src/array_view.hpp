#pragma once
// NumPy arrays in, spans out: the one conversion every binding needs.
#include <pybind11/numpy.h>

#include <cstddef>
#include <span>
#include <string>

#include "imunoise/error.hpp"

namespace imunoise::python {

/// A float64, C-contiguous view of any array-like (converted once when it is not).
using Array = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

/// The samples of a 1-D array; any other shape is the caller's InputError.
inline std::span<const double> view(const Array& a) {
  if (a.ndim() != 1) {
    throw InputError("data must be a 1-D array, got " + std::to_string(a.ndim()) + "-D");
  }
  return {a.data(), static_cast<std::size_t>(a.shape(0))};
}

}  // namespace imunoise::python
