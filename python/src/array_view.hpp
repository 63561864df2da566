#pragma once
// NumPy arrays in, spans out, and the sample rate that goes with them: the checks every
// binding needs.
#include <pybind11/numpy.h>

#include <cstddef>
#include <span>
#include <cmath>
#include <string>
#include <string_view>

#include <fmt/core.h>

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

/// `rate` (Hz), or the InputError that says what it must be; `alternative` names another way
/// to give it ("time=").
inline double checked_rate_hz(double rate, std::string_view alternative = {}) {
  if (!(rate > 0.0) || !std::isfinite(rate)) {
    throw InputError(fmt::format("rate must be positive and finite (Hz){}; got {:g}",
                                 alternative.empty() ? "" : fmt::format(", or given by {}", alternative), rate));
  }
  return rate;
}

}  // namespace imunoise::python
