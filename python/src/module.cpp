// Python bindings: one register_<concept> function per file; this file only assembles them.
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace imunoise::python {
void register_deviation(py::module_& m);
void register_simulate(py::module_& m);
void register_fit(py::module_& m);
void register_nav(py::module_& m);
void register_allantools(py::module_& m);
void register_redundant(py::module_& m);
void register_study(py::module_& m);
void register_recording(py::module_& m);  // imunoise.read, imunoise.dev (recordings, preprocessing)
}

PYBIND11_MODULE(_imunoise, m) {
  m.doc() = "imunoise: noise analysis of inertial sensors (compiled core)";
  imunoise::python::register_deviation(m);
  imunoise::python::register_simulate(m);
  imunoise::python::register_fit(m);
  imunoise::python::register_nav(m);
  imunoise::python::register_allantools(m);
  imunoise::python::register_redundant(m);
  imunoise::python::register_study(m);
  imunoise::python::register_recording(m);
}
