#pragma once
// The library's documents as Python objects, converted in memory (no JSON text in between):
// objects become dicts, arrays lists, numbers int or float, and a non-finite number None, as
// the JSON text of the command line writes it (null).
#include <pybind11/pybind11.h>

#include <cmath>

#include <nlohmann/json.hpp>

namespace imunoise::python {

inline pybind11::object to_python(const nlohmann::json& value) {
  namespace py = pybind11;
  switch (value.type()) {
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, item] : value.items()) out[py::str(key)] = to_python(item);
      return std::move(out);
    }
    case nlohmann::json::value_t::array: {
      py::list out(value.size());
      for (std::size_t i = 0; i < value.size(); ++i) out[i] = to_python(value[i]);
      return std::move(out);
    }
    case nlohmann::json::value_t::string: return py::str(value.get_ref<const std::string&>());
    case nlohmann::json::value_t::boolean: return py::bool_(value.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(value.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(value.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      const double v = value.get<double>();
      return std::isfinite(v) ? py::object(py::float_(v)) : py::none();
    }
    default: return py::none();
  }
}

}  // namespace imunoise::python
