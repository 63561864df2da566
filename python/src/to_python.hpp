#pragma once
// The library's documents as Python objects, converted in memory (no JSON text in between):
// objects become dicts, arrays lists, numbers int or float, and a non-finite number None, as
// the JSON text of the command line writes it (null); and back, for a document the user passes
// in (a fit dict given to nav or redundant).
#include <pybind11/pybind11.h>

#include <cmath>
#include <string>

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

/// A Python document (dicts, lists, str, bool, int, float, None) as the library's document.
/// Anything else is a TypeError naming where it is (`where`, e.g. "fit").
inline nlohmann::json from_python(const pybind11::handle& value, const std::string& where) {
  namespace py = pybind11;
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<std::int64_t>();
  if (py::isinstance<py::float_>(value)) {
    const double v = value.cast<double>();
    // The documents write a missing number as None (null); a NaN here is a broken value.
    if (!std::isfinite(v)) throw py::value_error(where + " is " + py::str(value).cast<std::string>() + "; use None for a value that is absent");
    return v;
  }
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, item] : value.cast<py::dict>()) {
      const std::string name = py::str(key).cast<std::string>();
      out[name] = from_python(item, where + "['" + name + "']");
    }
    return out;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nlohmann::json out = nlohmann::json::array();
    std::size_t i = 0;
    for (const auto& item : value) out.push_back(from_python(item, where + "[" + std::to_string(i++) + "]"));
    return out;
  }
  throw py::type_error(where + ": " + py::str(py::type::of(value)).cast<std::string>() +
                       " is not a JSON document value (dict, list, str, number, bool or None)");
}

}  // namespace imunoise::python
