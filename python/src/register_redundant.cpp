// imunoise.redundant and imunoise.fuse: the redundant gyro unit from Python, returning the
// document of `imunoise redundant --format json` (a dict) built by the library.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/error.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/redundant/in_motion.hpp"
#include "imunoise/redundant/report.hpp"
#include "imunoise/redundant/unit_simulation.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/study/in_motion.hpp"
#include "imunoise/study/in_motion_container.hpp"
#include "imunoise/study/sensor.hpp"
#include "imunoise/units.hpp"
#include "to_python.hpp"

#include "array_view.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Each fit is a dict (imunoise.fit's result) or a path to a JSON file of `imunoise fit`.
std::vector<redundant::SensorModel> models_of(const py::object& fits, Unit& unit) {
  std::vector<redundant::SensorModel> models;
  if (fits.is_none()) return models;
  std::string first;
  std::size_t i = 0;
  for (const auto& item : fits) {
    ++i;
    Unit u;
    if (py::isinstance<py::dict>(item)) {
      const std::string where = "fits[" + std::to_string(i - 1) + "]";
      models.push_back(redundant::sensor_model_from_fit_json(from_python(item, where), where, u));
    } else {
      const std::filesystem::path path(py::str(item).cast<std::string>());
      std::vector<std::filesystem::path> one{path};
      models.push_back(redundant::read_fit_files(one, u).front());
    }
    if (i == 1) {
      unit = u;
    } else if (u.name != unit.name) {
      throw InputError("fits[" + std::to_string(i - 1) + "] is in " + u.name + " but fits[0] is in " +
                       unit.name + ": fit every gyro in the same unit");
    }
  }
  return models;
}

redundant::DetectionOptions detection_options(double window_s, double reference_s, double false_alarm_per_hour,
                                              double detection_probability) {
  redundant::DetectionOptions o;
  o.window_s = window_s;
  o.reference_s = reference_s;
  o.false_alarm_per_hour = false_alarm_per_hour;
  o.detection_probability = detection_probability;
  std::string why;
  if (!o.IsValid(&why)) throw InputError("detection options: " + why);
  return o;
}

// Without units or fits the numbers are used as given (fusion is linear) and labelled
// "input unit".
Unit resolve_unit(const std::string& units, const Unit& from_fits, bool have_fits) {
  if (units.empty()) return have_fits ? from_fits : Unit{"input unit", Quantity::angular_rate, 1.0};
  const Unit u = parse_unit(units);
  if (u.quantity != Quantity::angular_rate) throw InputError("units '" + units + "' is not an angular rate (e.g. deg/s)");
  if (have_fits && from_fits.name != "input unit" && from_fits.name != u.name) {
    throw InputError("units='" + units + "' but the fits are in " + from_fits.name + "; use one unit");
  }
  return u;
}

py::object redundant_analysis(const std::string& geometry, const py::object& fits, const std::string& units,
                              double window_s, double reference_s, double false_alarm_per_hour,
                              double detection_probability) {
  const auto g = redundant::make_geometry(geometry);
  Unit fit_unit;
  const auto models = models_of(fits, fit_unit);
  const Unit unit = resolve_unit(units, fit_unit, !models.empty());
  redundant::AnalysisOptions ao;
  ao.detection = detection_options(window_s, reference_s, false_alarm_per_hour, detection_probability);
  return to_python(redundant::report_json(redundant::analyze_unit(g, models, ao), unit));
}

py::array_t<double> owned_array(std::vector<double>&& v) {
  auto* owned = new std::vector<double>(std::move(v));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(static_cast<py::ssize_t>(owned->size()), owned->data(), free_when_done);
}

// records: a 2-D array (sensors x samples) or a sequence of 1-D arrays, in `unit`, -> SI.
std::vector<std::vector<double>> records_si(const py::object& records, const Unit& unit) {
  std::vector<Array> arrays;
  const Array as2d = py::isinstance<py::array>(records) ? Array::ensure(records) : Array();
  if (as2d && as2d.ndim() == 2) {
    for (py::ssize_t i = 0; i < as2d.shape(0); ++i) arrays.push_back(Array::ensure(records.attr("__getitem__")(i)));
  } else {
    for (const auto& r : records) arrays.push_back(Array::ensure(r));
  }
  std::vector<std::vector<double>> si;
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    const auto& a = arrays[i];
    if (!a || a.ndim() != 1) throw InputError("records[" + std::to_string(i) + "] must be a 1-D array");
    std::vector<double> v(a.data(), a.data() + a.shape(0));
    if (const std::size_t k = first_non_finite(v, 0); k < v.size()) {
      throw InputError("records[" + std::to_string(i) + "]: sample " + std::to_string(k) + " is not finite");
    }
    for (auto& x : v) x *= unit.to_si;
    si.push_back(std::move(v));
  }
  return si;
}

// The `in_motion` document of `imunoise redundant --in-motion` for arrays.
// records: sensors x samples (arrays), or the path of a container holding the whole unit (a PX4
// log, a bag: study::read_container_unit with `topic`, comma list, and `accel_topic`).
py::object in_motion(const py::object& records, const std::string& geometry, double rate, const std::string& units,
                     bool per_sensor, double ci, bool remove_leakage, const py::object& static_records,
                     const std::string& topic, const py::object& accel_topic, const py::object& specific_force,
                     bool timing) {
  const auto g = redundant::make_geometry(geometry);
  checked_rate_hz(rate);
  Unit unit = resolve_unit(units, Unit{}, false);
  std::vector<Record> recs;
  std::array<std::vector<double>, 3> force;
  std::vector<std::string> container_notes;
  redundant::InMotionOptions options;
  if (py::isinstance<py::str>(records) || py::isinstance(records, py::module_::import("pathlib").attr("PurePath"))) {
    if (!specific_force.is_none()) {
      throw InputError("specific_force is for arrays; a container's accelerometers: accel_topic");
    }
    load::LoadOptions lo;
    lo.file = py::str(records).cast<std::string>();
    lo.units = units;
    std::vector<std::string> topics;
    for (std::size_t b = 0; b <= topic.size() && !topic.empty();) {
      const auto c = topic.find(',', b);
      const auto piece = topic.substr(b, c == std::string::npos ? std::string::npos : c - b);
      if (!piece.empty()) topics.push_back(piece);
      if (c == std::string::npos) break;
      b = c + 1;
    }
    std::vector<std::string> accel_topics;
    if (py::isinstance<py::str>(accel_topic)) accel_topics.push_back(accel_topic.cast<std::string>());
    else if (!accel_topic.is_none()) accel_topics = accel_topic.cast<std::vector<std::string>>();
    auto cu = study::read_container_unit(lo, topics, accel_topics);
    recs = std::move(cu.gyros);
    force = std::move(cu.specific_force_m_s2);
    container_notes = std::move(cu.notes);
    unit = recs.front().rate_unit;
    options.remove_timing_leakage = true;
  } else {
    auto si = records_si(records, unit);
    for (std::size_t i = 0; i < si.size(); ++i) {
      recs.push_back(rate_record("records[" + std::to_string(i) + "]", std::move(si[i]), rate, unit, !units.empty()));
    }
    if (!specific_force.is_none()) {
      auto f = records_si(specific_force, Unit{"m/s^2", Quantity::acceleration, 1.0});
      if (f.size() != 3) throw InputError("specific_force: give 3 arrays (x, y, z of the body, m/s^2)");
      for (std::size_t a = 0; a < 3; ++a) force[a] = std::move(f[a]);
    }
    options.remove_timing_leakage = timing;
  }
  options.require_per_sensor = per_sensor;
  options.ci_level = ci;
  options.remove_leakage = remove_leakage;
  const fit::FitOptions fit_options;
  std::vector<Record> statics;
  if (!static_records.is_none()) {
    auto st = records_si(static_records, unit);
    for (std::size_t i = 0; i < st.size(); ++i) {
      Record r;
      r.name = r.source = "static_records[" + std::to_string(i) + "]";
      r.rate_hz = rate;
      r.rate_unit = unit;
      r.unit_given = !units.empty();
      statics.push_back(load::finish_rates(std::move(r), std::move(st[i]), {}));
    }
  }
  nlohmann::json doc;
  {
    py::gil_scoped_release release;
    auto result = study::analyze_in_motion(g, std::move(recs), options, fit_options, force);
    result.notes.insert(result.notes.begin(), container_notes.begin(), container_notes.end());
    if (!static_records.is_none()) study::compare_with_static(result, std::move(statics), fit_options);
    doc = study::in_motion_json(result, fit_options);
  }
  return to_python(doc);
}

// One value per sensor from a scalar or a sequence of n.
std::vector<double> per_sensor_values(const py::object& v, std::size_t n, const char* name) {
  if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return std::vector<double>(n, v.cast<double>());
  auto out = v.cast<std::vector<double>>();
  if (out.size() != n) {
    throw InputError(std::string(name) + ": " + std::to_string(out.size()) + " values for " + std::to_string(n) +
                     " sensors; give one per sensor or a single value");
  }
  return out;
}

// A unit under motion in `units` (the noise terms in units of the rate, as imunoise.simulate).
py::array_t<double> simulate_unit(const std::string& geometry, double rate, double duration, const std::string& units,
                                  const py::object& n, const py::object& b, const py::object& k,
                                  const py::object& scale_factor_ppm, const py::object& misalignment_mrad,
                                  const py::object& motion_noise, double tumble, const std::vector<double>& turn,
                                  std::uint64_t seed) {
  const auto g = redundant::make_geometry(geometry);
  checked_rate_hz(rate);
  const Unit unit = resolve_unit(units, Unit{}, false);
  const std::size_t count = g.size();
  const auto nv = per_sensor_values(n, count, "N");
  const auto bv = per_sensor_values(b, count, "B");
  const auto kv = per_sensor_values(k, count, "K");
  const auto sf = per_sensor_values(scale_factor_ppm, count, "scale_factor_ppm");
  const auto mn = per_sensor_values(motion_noise, count, "motion_noise");
  std::vector<std::vector<double>> mis(count, std::vector<double>(3, 0.0));
  if (!misalignment_mrad.is_none()) {
    mis = misalignment_mrad.cast<std::vector<std::vector<double>>>();
    if (mis.size() != count || std::any_of(mis.begin(), mis.end(), [](const auto& r) { return r.size() != 3; })) {
      throw InputError("misalignment_mrad: give one [x, y, z] (mrad) per sensor");
    }
  }
  if (turn.size() != 3) throw InputError("turn: give [x, y, z] in the rate unit");
  std::vector<redundant::UnitSensor> sensors(count);
  for (std::size_t i = 0; i < count; ++i) {
    sensors[i].noise.n_unit_sqrt_s = nv[i] * unit.to_si;
    sensors[i].noise.b_unit = bv[i] * unit.to_si;
    sensors[i].noise.k_unit_per_sqrt_s = kv[i] * unit.to_si;
    sensors[i].scale_factor_ppm = sf[i];
    for (std::size_t a = 0; a < 3; ++a) sensors[i].misalignment_rad[a] = 1e-3 * mis[i][a];
    sensors[i].motion_noise_sqrt_s = mn[i];
  }
  auto motion = redundant::tumble_profile(tumble * unit.to_si);
  for (std::size_t a = 0; a < 3; ++a) motion.constant_rad_s[a] = turn[a] * unit.to_si;
  std::vector<std::vector<double>> rec;
  {
    py::gil_scoped_release release;
    rec = redundant::simulate_unit(g, sensors, motion, rate, duration, seed);
  }
  const std::size_t len = rec.empty() ? 0 : rec[0].size();
  py::array_t<double> out({static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(len)});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t t = 0; t < len; ++t) {
      view(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(t)) = rec[i][t] / unit.to_si;
    }
  }
  return out;
}

py::dict fuse(const py::object& records, const std::string& geometry, double rate, const std::string& units,
              const py::object& fits, bool detect, double window_s, double reference_s,
              double false_alarm_per_hour, double detection_probability, unsigned threads) {
  const auto g = redundant::make_geometry(geometry);
  checked_rate_hz(rate);
  Unit fit_unit;
  auto models = models_of(fits, fit_unit);
  const Unit unit = resolve_unit(units, fit_unit, !models.empty());
  std::vector<std::vector<double>> si = records_si(records, unit);
  if (detect && models.empty()) {
    for (std::size_t i = 0; i < si.size(); ++i) {
      Record record;
      record.name = record.source = "records[" + std::to_string(i) + "]";
      record.rate_hz = rate;
      record.rate_unit = Unit{"rad/s", Quantity::angular_rate, 1.0};
      record.unit_given = true;
      models.push_back(study::sensor_model(load::finish_rates(std::move(record), si[i], {})));
    }
  }
  redundant::AnalysisOptions ao;
  ao.detection = detection_options(window_s, reference_s, false_alarm_per_hour, detection_probability);
  redundant::FusionOptions fo;
  fo.detect = detect;
  fo.detection = ao.detection;
  fo.threads = threads;
  std::vector<std::span<const double>> spans;
  for (const auto& v : si) spans.emplace_back(v);
  redundant::Analysis analysis;
  redundant::FusedRecord fused;
  {
    py::gil_scoped_release release;
    analysis = redundant::analyze_unit(g, models, ao);
    fused = redundant::fuse_records(analysis, spans, rate, fo);
  }
  const double f = 1.0 / unit.to_si;
  py::dict out;
  const char* names[3] = {"x", "y", "z"};
  for (std::size_t j = 0; j < 3; ++j) {
    for (auto& v : fused.axes_rad_s[j]) v *= f;
    out[names[j]] = owned_array(std::move(fused.axes_rad_s[j]));
  }
  py::list parity;
  for (auto& p : fused.parity_rad_s) {
    for (auto& v : p) v *= f;
    parity.append(owned_array(std::move(p)));
  }
  out["parity"] = parity;
  out["rate_hz"] = rate;
  out["unit"] = unit.name;
  out["report"] = to_python(redundant::report_json(analysis, unit, fused.detection ? &*fused.detection : nullptr));
  return out;
}

}  // namespace

void register_redundant(py::module_& m) {
  m.def("redundant", &redundant_analysis, py::arg("geometry"), py::arg("fits") = py::none(),
        py::arg("units") = "", py::arg("window_s") = 1.0, py::arg("reference_s") = 60.0,
        py::arg("false_alarm_per_hour") = 0.01, py::arg("detection_probability") = 0.99,
        "Redundant gyro unit: geometry ('tetra', 'cone:N:DEG', '3+1', 'dodeca' or a file), optionally "
        "each sensor's fit (dicts from imunoise.fit or fit JSON paths) -> the dict of "
        "`imunoise redundant --format json` (gains, GDOP, parity, fused-axis N/B/K, detection design)");
  m.def("in_motion", &in_motion, py::arg("records"), py::arg("geometry"), py::arg("rate") = 1.0,
        py::arg("units") = "", py::arg("per_sensor") = false, py::arg("ci") = 0.683,
        py::arg("remove_leakage") = true, py::arg("static_records") = py::none(), py::arg("topic") = "",
        py::arg("accel_topic") = py::none(), py::arg("specific_force") = py::none(), py::arg("timing") = false,
        "Each sensor's noise while the unit moves (the N-cornered hat in parity space): synchronous "
        "records (sensors x samples, in `units`) through the geometry -> the `in_motion` dict of "
        "`imunoise redundant --in-motion` (identifiability, common level, leakage, sensors with curve, "
        "fit and leakage, or identified False and the reason). remove_leakage=False keeps the motion "
        "leaking through scale-factor and misalignment errors; per_sensor=True raises ValueError when "
        "the geometry cannot give every sensor its own curve. static_records (the same sensors at rest, "
        "same order, rate and units) adds each sensor's static_fit and the in-motion/static "
        "inflation of N, B, K. records may also be the path of a container holding the whole unit (a PX4 "
        "log: topic='sensor_gyro', accel_topic='sensor_accel'; a bag: topic='/imu0,/imu1,/imu2'), its "
        "instances paired sample by sample and the timing leakage removed (rate and units from the file). "
        "specific_force (3 arrays, m/s^2, with arrays) estimates and removes the gyros' g-sensitivity; "
        "timing=True the leakage of sensors sampled at different instants.");
  m.def("simulate_unit", &simulate_unit, py::arg("geometry"), py::arg("rate"), py::arg("duration"),
        py::arg("units") = "deg/s", py::arg("N") = 0.0, py::arg("B") = 0.0, py::arg("K") = 0.0,
        py::arg("scale_factor_ppm") = 0.0, py::arg("misalignment_mrad") = py::none(),
        py::arg("motion_noise") = 0.0, py::arg("tumble") = 0.0,
        py::arg("turn") = std::vector<double>{0.0, 0.0, 0.0}, py::arg("seed") = 1,
        "A redundant unit under motion -> records[sensors, samples] in `units`: each sensor's N, B, K "
        "(scalars or one per sensor, in units of the rate as imunoise.simulate), scale factor (ppm), "
        "misalignment ([x, y, z] mrad per sensor), motion_noise (sqrt(s): extra white noise of "
        "density motion_noise |h . w|), under rotations to `tumble` on every axis (0.5, 0.31, 0.17 Hz) "
        "plus a steady `turn` [x, y, z]; reproducible from `seed`.");
  m.def("fuse", &fuse, py::arg("records"), py::arg("geometry"), py::arg("rate") = 1.0, py::arg("units") = "",
        py::arg("fits") = py::none(), py::arg("detect") = false, py::arg("window_s") = 1.0,
        py::arg("reference_s") = 60.0, py::arg("false_alarm_per_hour") = 0.01,
        py::arg("detection_probability") = 0.99, py::arg("threads") = 1,
        "Fuse synchronous gyro records (sensors x samples, in `units`) through the geometry -> dict "
        "with arrays x, y, z (fused body rates), parity (list of p_1..p_k), and report (the JSON "
        "document; with detect=True its 'faults'). Without fits, detection fits each record itself.");
}

}  // namespace imunoise::python
