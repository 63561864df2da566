// imunoise.read: a recording (ROS 1 bag, ROS 2 MCAP, HDF5, EuRoC CSV, text or raw binary) as a
// Python object with its channel names, units, NumPy arrays, timestamps, rate and source; and
// imunoise.dev: deviation curves of rate samples with the preprocessing options, as the
// document of `imunoise dev --format json`. Only parses and calls the library (imunoise/load,
// imunoise/preprocess, imunoise/study).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/io/recording.hpp"
#include "imunoise/load/read_channels.hpp"
#include "imunoise/study/curves.hpp"
#include "imunoise/tau_grid.hpp"
#include "preprocessing.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "to_python.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

using PyRecording = load::FileRecording;

py::array_t<double> to_numpy(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

std::vector<std::string> names_of(const py::object& value) {
  if (value.is_none()) return {};
  if (py::isinstance<py::str>(value)) return {value.cast<std::string>()};
  if (py::isinstance<py::int_>(value)) return {std::to_string(value.cast<long long>())};
  std::vector<std::string> out;
  for (const auto& item : value) {
    out.push_back(py::isinstance<py::int_>(item) ? std::to_string(item.cast<long long>()) : py::str(item).cast<std::string>());
  }
  return out;
}

PyRecording read(const std::string& path, const std::optional<std::string>& topic,
                 const std::optional<std::string>& dataset, const std::optional<std::string>& time_dataset,
                 const py::object& column, const py::object& time_column, const std::optional<std::string>& binary,
                 std::size_t channels, const std::optional<double>& rate) {
  load::ChannelsOptions options;
  options.file = path;
  options.topic = topic.value_or("");
  options.dataset = dataset.value_or("");
  options.time_dataset = time_dataset.value_or("");
  options.columns = names_of(column);
  const std::vector<std::string> time_names = names_of(time_column);
  if (time_names.size() > 1) throw InputError("time_column names one column");
  if (!time_names.empty()) options.time_column = time_names[0];
  options.binary = binary.value_or("");
  options.channels = channels;
  options.rate_hz = rate;
  py::gil_scoped_release release;
  return load::read_channels(options);
}

const io::Channel& channel_of(const PyRecording& r, const py::object& key) {
  return r.recording.channel(names_of(key).at(0));
}

py::object dev(const Array& data, const py::object& rate, const py::object& estimators, const std::string& units,
               const std::string& taus, double level, const std::optional<std::string>& noise_type, bool no_ci,
               unsigned threads, const py::object& time, const py::object& skip, const std::string& detrend,
               const py::object& outliers, const std::string& gaps, bool davar, double davar_window,
               const py::object& temperature, double temperature_bin) {
  if (data.ndim() != 1) throw InputError("data must be a 1-D array of rate samples, got " + std::to_string(data.ndim()) + "-D");
  PreprocessArgs args{time, skip, detrend, outliers, gaps, davar, davar_window, temperature, temperature_bin};
  study::CurveOptions options;
  std::string names = "oadev";
  if (!estimators.is_none()) {
    names.clear();
    for (const auto& n : names_of(estimators)) names += (names.empty() ? "" : ",") + n;
  }
  options.estimators = parse_estimator_list(names);
  options.grid = parse_tau_grid(taus);
  if (!no_ci) validate_confidence_level(level, "level");
  options.ci_level = level;
  options.no_ci = no_ci;
  if (noise_type) options.forced_alpha = parse_noise_type(*noise_type);
  options.threads = threads;
  nlohmann::json document;
  PreparedRecord prepared =
      prepare_record({data.data(), static_cast<std::size_t>(data.shape(0))}, rate, units, args, std::nullopt);
  {
    py::gil_scoped_release release;
    const auto curves = study::compute_curves(prepared.record, options);
    auto array = study::curves_json(prepared.record, curves);
    for (auto& object : array) study::add_provenance(prepared.record, fit::FitOptions{}, object);
    document = array.size() == 1 ? array[0] : array;
  }
  return to_python(document);
}

}  // namespace

void register_recording(py::module_& m) {
  py::class_<PyRecording>(m, "Recording", "A recording read by imunoise.read: named channels sharing one set of timestamps.")
      .def_property_readonly("source", [](const PyRecording& r) { return r.recording.source; })
      .def_property_readonly("format", [](const PyRecording& r) { return std::string(io::format_name(r.recording.format)); },
                             "'ROS 1 bag', 'ROS 2 bag (SQLite)', 'MCAP', 'PX4 ULog', 'HDF5', 'EuRoC CSV', 'text' or 'binary'")
      .def_property_readonly("stream", [](const PyRecording& r) { return r.recording.stream; },
                             "topic or dataset read ('' for text, binary, EuRoC)")
      .def_property_readonly("message_type", [](const PyRecording& r) { return r.recording.message_type; })
      .def_property_readonly("notes", [](const PyRecording& r) { return r.recording.notes; },
                             "what the reader found that you should know (e.g. PX4 logger dropouts)")
      .def_property_readonly("time_origin", [](const PyRecording& r) { return r.recording.time_origin; },
                             "the first timestamp as stored (e.g. '1403636579758555392 ns')")
      .def_property_readonly("channel_names", [](const PyRecording& r) {
        std::vector<std::string> names;
        for (const auto& c : r.recording.channels) names.push_back(c.name);
        return names;
      })
      .def_property_readonly("units", [](const PyRecording& r) {
        py::dict units;
        for (const auto& c : r.recording.channels) {
          units[py::str(c.name)] = c.unit ? py::object(py::str(c.unit->name)) : py::object(py::none());
        }
        return units;
      }, "unit of each channel as the file states it (None when it does not)")
      .def_property_readonly("time_s", [](const PyRecording& r) -> py::object {
        if (r.recording.time_s.empty()) return py::none();
        return to_numpy(r.recording.time_s);
      }, "seconds since the first sample (None when the file has no timestamps)")
      .def_property_readonly("rate", [](const PyRecording& r) -> py::object {
        if (!std::isfinite(r.rate_hz)) return py::none();
        return py::float_(r.rate_hz);
      }, "sample rate (Hz): 1 / the median interval of the timestamps, or rate= for files without")
      .def_property_readonly("gaps", [](const PyRecording& r) {
        py::list gaps;
        if (r.timing) {
          for (const auto& g : r.timing->gaps) gaps.append(py::make_tuple(g.index, g.duration_s, g.missing_samples));
        }
        return gaps;
      }, "timestamp gaps as (first sample after the gap, interval s, missing samples)")
      .def("channel", [](const PyRecording& r, const py::object& key) { return to_numpy(channel_of(r, key).values); },
           py::arg("name"), "the samples of a channel (by name, or 0-based index) as a NumPy array")
      .def("__getitem__", [](const PyRecording& r, const py::object& key) { return to_numpy(channel_of(r, key).values); })
      .def("__len__", [](const PyRecording& r) { return r.recording.sample_count(); })
      .def("__contains__", [](const PyRecording& r, const std::string& name) {
        for (const auto& c : r.recording.channels) if (c.name == name) return true;
        return false;
      })
      .def("to_array", [](const PyRecording& r) {
        const std::size_t n = r.recording.sample_count();
        const std::size_t k = r.recording.channels.size();
        py::array_t<double> a({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(k)});
        auto view = a.mutable_unchecked<2>();
        for (std::size_t c = 0; c < k; ++c) {
          for (std::size_t i = 0; i < n; ++i) view(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(c)) = r.recording.channels[c].values[i];
        }
        return a;
      }, "all channels as an (n_samples, n_channels) array, columns in channel_names order")
      .def("__repr__", [](const PyRecording& r) {
        std::string text = "<imunoise.Recording " + r.recording.source + " (" + std::string(io::format_name(r.recording.format));
        if (!r.recording.stream.empty()) text += " " + r.recording.stream;
        text += "): " + std::to_string(r.recording.sample_count()) + " samples of " + r.recording.channel_list();
        if (std::isfinite(r.rate_hz)) text += fmt::format(" at {:.6g} Hz", r.rate_hz);
        return text + ">";
      });
  m.def("read", &read, py::arg("path"), py::arg("topic") = py::none(), py::arg("dataset") = py::none(),
        py::arg("time_dataset") = py::none(), py::arg("column") = py::none(), py::arg("time_column") = py::none(),
        py::arg("binary") = py::none(), py::arg("channels") = 1, py::arg("rate") = py::none(),
        R"(read(path, topic=None, dataset=None, time_dataset=None, column=None, time_column=None,
     binary=None, channels=1, rate=None) -> Recording

Reads a recording: a ROS 1 bag, ROS 2 bag (.db3 or its directory) or MCAP file (topic= of
sensor_msgs Imu: channels gyro_x gyro_y gyro_z accel_x accel_y accel_z in rad/s and m/s^2,
timestamps from header.stamp), a PX4 ULog (topic='sensor_combined', 'vehicle_imu',
'sensor_gyro', ...: several instances give gyro0_x ...; choose one instance's channels with
column=), an
HDF5 file (dataset= 1-D or 2-D, time_dataset= optional), a EuRoC imu0/data.csv, a text file
(column= names or indices, time_column=) or raw binary samples (binary='f32' etc., channels=,
rate=). column= keeps only those channels. The rate comes from the timestamps (median
interval), or rate= when the file has none. A wrong topic or dataset raises ValueError
listing what the file holds.)");
  m.def("dev", &dev, py::arg("data"), py::arg("rate") = py::none(), py::arg("estimators") = py::none(),
        py::arg("units") = "", py::arg("taus") = "octave", py::arg("level") = 0.683,
        py::arg("noise_type") = py::none(), py::arg("no_ci") = false, py::arg("threads") = 0u,
        py::arg("time") = py::none(), py::arg("skip") = py::none(), py::arg("detrend") = "none",
        py::arg("outliers") = py::none(), py::arg("gaps") = "fail", py::arg("davar") = false,
        py::arg("davar_window") = 0.0, py::arg("temperature") = py::none(), py::arg("temperature_bin") = 5.0,
        R"(dev(data, rate=None, estimators='oadev', units='', taus='octave', level=0.683, noise_type=None,
    no_ci=False, threads=0, time=None, skip=None, detrend='none', outliers=None, gaps='fail',
    davar=False, davar_window=0.0, temperature=None, temperature_bin=5.0) -> dict or list

Deviation curves of rate samples with n, EDF and confidence bounds: the document of
`imunoise dev --format json` (a dict for one estimator, a list for several). Preprocessing as
the command line's options: time= timestamps (s) give the rate and the gaps; skip= seconds,
'5min' or 'auto'; detrend= 'linear'/'quadratic'; outliers= 'fail'/'report'/'reject';
gaps= 'fail'/'split'/'allow' (split: segments pooled for adev oadev mdev tdev hdev ohdev,
never interpolated); davar=True; temperature= one value per sample, binned by
temperature_bin with a fit per bin. What each step removed is under "preprocessing".)");
}

}  // namespace imunoise::python
