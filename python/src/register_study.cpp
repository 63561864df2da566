// imunoise.analyze: the whole study (curves, fit, datasheet, navigation, fusion) of NumPy rate
// records, as the report document of `imunoise analyze` (report.json) in a dict; optionally
// the report directory too. Only parses and calls the library's study pipeline
// (imunoise/study): the records are built as the command line builds them from files.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "imunoise/comma_list.hpp"
#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/spec/spec.hpp"
#include "imunoise/study/record.hpp"
#include "imunoise/study/study.hpp"
#include "imunoise/study/write.hpp"
#include "imunoise/units.hpp"

#include "preprocessing.hpp"
#include "imunoise/load/load.hpp"
#include "to_python.hpp"

#include "array_view.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A comma string or a list of strings; empty when None.
std::vector<std::string> string_list(const py::object& value, const char* what) {
  std::vector<std::string> out;
  if (value.is_none()) return out;
  if (py::isinstance<py::str>(value)) return split_comma_list(value.cast<std::string>());
  try {
    return value.cast<std::vector<std::string>>();
  } catch (const py::cast_error&) {
    throw InputError(std::string(what) + " must be a string (comma list) or a list of strings");
  }
}

// The channels as columns of samples: a 1-D array (one channel), a 2-D array (columns are
// channels) or a list of 1-D arrays of one length.
std::vector<std::vector<double>> channel_columns(const py::object& channels) {
  std::vector<std::vector<double>> out;
  if (py::isinstance<py::list>(channels) || py::isinstance<py::tuple>(channels)) {
    const auto items = channels.cast<std::vector<py::object>>();
    if (items.empty()) throw InputError("channels is an empty list: give at least one 1-D array of rate samples");
    for (std::size_t i = 0; i < items.size(); ++i) {
      const Array a = Array::ensure(items[i]);
      if (!a) throw InputError("channels[" + std::to_string(i) + "] is not an array of numbers");
      if (a.ndim() != 1) {
        throw InputError("channels[" + std::to_string(i) + "] must be a 1-D array, got " +
                         std::to_string(a.ndim()) + "-D");
      }
      out.emplace_back(a.data(), a.data() + a.shape(0));
      if (out.back().size() != out.front().size()) {
        throw InputError("channels[" + std::to_string(i) + "] has " + std::to_string(out.back().size()) +
                         " samples but channels[0] has " + std::to_string(out.front().size()) +
                         ": the channels of one recording must have one length; trim them");
      }
    }
    return out;
  }
  const Array a = Array::ensure(channels);
  if (!a) throw InputError("channels must be a NumPy array (1-D or 2-D) or a list of 1-D arrays");
  if (a.ndim() == 1) {
    out.emplace_back(a.data(), a.data() + a.shape(0));
  } else if (a.ndim() == 2) {
    const auto rows = static_cast<std::size_t>(a.shape(0));
    const auto cols = static_cast<std::size_t>(a.shape(1));
    out.assign(cols, std::vector<double>(rows));
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < cols; ++c) out[c][r] = a.data()[r * cols + c];
    }
    if (cols == 0) throw InputError("channels is a 2-D array with no columns: columns are the channels");
  } else {
    throw InputError("channels must be 1-D or 2-D (columns are channels), got " + std::to_string(a.ndim()) + "-D");
  }
  return out;
}

// The record of one channel of rate samples in `units` ("" : not given), as the loader builds
// it from a file (load::finish_rates): samples to SI, offset removed, integrated into the phase.
study::Record make_record(std::vector<double> rate, double rate_hz, const std::string& units,
                          std::string name, std::string source) {
  study::Record r;
  r.name = std::move(name);
  r.source = std::move(source);
  r.kind = InputKind::rate;
  r.rate_hz = rate_hz;
  r.n_samples = rate.size();
  if (rate.empty()) throw InputError(r.name + ": no samples; give at least a few hundred rate samples");
  if (const std::size_t i = first_non_finite(rate); i < rate.size()) {
    throw InputError(r.name + ": sample " + std::to_string(i) + " is not finite (NaN or inf); remove or repair it");
  }
  r.unit_given = !units.empty();
  r.rate_unit = rate_unit_of(units);
  scale_to_si(rate, r.rate_unit);
  return load::finish_rates(std::move(r), std::move(rate), {});
}

py::object analyze(const py::object& channels, double rate, const py::object& units,
                   const py::object& names, const std::optional<std::string>& spec,
                   const std::optional<std::string>& geometry,
                   double nav_hours, const std::string& nav_models, const py::object& estimators, bool keep_going,
                   const py::object& output_dir, bool force) {
  checked_rate_hz(rate);
  if (!(nav_hours > 0.0) || !std::isfinite(nav_hours)) {
    throw InputError("nav_hours must be positive and finite (h)");
  }
  auto columns = channel_columns(channels);
  const auto name_list = string_list(names, "names");
  if (!name_list.empty() && name_list.size() != columns.size()) {
    throw InputError("names gives " + std::to_string(name_list.size()) + " names for " +
                     std::to_string(columns.size()) + " channels; give one name per channel");
  }
  const auto unit_list = string_list(units, "units");
  if (unit_list.size() > 1 && unit_list.size() != columns.size()) {
    throw InputError("units gives " + std::to_string(unit_list.size()) + " units for " +
                     std::to_string(columns.size()) + " channels; give one unit for all, or one per channel");
  }

  study::StudyOptions so;
  const auto estimator_names = string_list(estimators, "estimators");
  if (!estimator_names.empty()) {
    std::string joined;
    for (const auto& e : estimator_names) joined += (joined.empty() ? "" : ",") + e;
    so.curves.estimators = parse_estimator_list(joined);
  }
  if (spec && !spec->empty()) so.spec = resolve_spec(*spec);
  so.geometry = geometry.value_or("");
  so.nav_hours = nav_hours;
  so.nav_models = nav_models;
  so.keep_going = keep_going;

  std::vector<study::Record> records;
  std::vector<study::FailedInput> failed;
  nlohmann::json doc;
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const std::string source = "channels[" + std::to_string(i) + "]";
      const std::string name =
          name_list.empty() ? (columns.size() == 1 ? std::string("channel") : "ch" + std::to_string(i)) : name_list[i];
      const std::string unit = unit_list.empty() ? std::string() : unit_list.size() == 1 ? unit_list[0] : unit_list[i];
      records.push_back(make_record(std::move(columns[i]), rate, unit, name, source));
    }
    const study::Study result = study::run_study(std::move(records), so, std::move(failed));
    doc = study::study_json(result);
  }
  py::object out = to_python(doc);
  if (!output_dir.is_none()) {
    const std::string dir = py::str(output_dir).cast<std::string>();
    study::WrittenReport written;
    {
      py::gil_scoped_release release;
      written = study::write_report(doc, dir, {force, "", "gnuplot"});
    }
    py::list files;
    for (const auto& f : written.files) files.append((std::filesystem::path(written.dir) / f).string());
    py::dict w;
    w["dir"] = written.dir;
    w["files"] = files;
    w["notes"] = written.notes;
    w["interactive"] = written.interactive;
    out["written"] = w;
  }
  return out;
}

}  // namespace

void register_study(py::module_& m) {
  m.def("analyze", &analyze, py::arg("channels"), py::arg("rate"), py::arg("units") = py::none(),
        py::arg("names") = py::none(), py::arg("spec") = py::none(), py::arg("geometry") = py::none(),
        py::arg("nav_hours") = 1.0, py::arg("nav_models") = "schuler,covariance,montecarlo", py::arg("estimators") = py::none(), py::arg("keep_going") = false,
        py::arg("output_dir") = py::none(), py::arg("force") = false,
        R"(analyze(channels, rate, units=None, names=None, spec=None, geometry=None, nav_hours=1.0, nav_models='schuler,covariance,montecarlo',
        estimators=None, keep_going=False, output_dir=None, force=False) -> dict

The whole study of rate records: the document `imunoise analyze` writes as report.json
(curves with confidence, fit, datasheet comparison, navigation error, redundant unit).
channels: a 1-D array, a 2-D array (columns are channels) or a list of 1-D arrays of one
length, of rate samples; rate in Hz; units: one unit for all (e.g. 'deg/s') or one per
channel; names: channel names; spec: datasheet name or YAML file; geometry: redundant-unit
geometry (e.g. 'tetra'); estimators: extra curves (oadev is always computed). With
output_dir, the report is also written there (existing files kept unless force) and the
written paths are under "written". Bad input raises ValueError.)");
}

}  // namespace imunoise::python
