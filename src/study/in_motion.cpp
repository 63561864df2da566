#include "imunoise/study/in_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/study/fit_stage.hpp"

namespace imunoise::study {
namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// Every check that makes the recordings one synchronous unit, naming the files.
void check_unit(const redundant::Geometry& geometry, const std::vector<Record>& recs) {
  const std::size_t n = geometry.size();
  if (recs.size() != n) {
    throw InputError(fmt::format("--in-motion: {} recordings for the {} sensors of geometry {}; give one per "
                                 "sensing axis, in the geometry's order", recs.size(), n, geometry.name));
  }
  if (n <= 3) {
    throw InputError(fmt::format("--in-motion: geometry {} has {} sensors for 3 axes, so no parity space: the "
                                 "in-motion analysis needs more sensors than axes (4 or more non-orthogonal "
                                 "gyros, or co-aligned triads)", geometry.name, n));
  }
  for (const auto& r : recs) {
    if (r.rate_si.empty()) throw InputError(r.source + ": no rate samples kept (internal: load with keep_rates)");
    if (std::abs(r.rate_hz / recs[0].rate_hz - 1.0) > 1e-6) {
      throw InputError(fmt::format("--in-motion: {} is sampled at {:.9g} Hz but {} at {:.9g} Hz: the recordings "
                                   "must be synchronous (resample them to one rate first)",
                                   r.source, r.rate_hz, recs[0].source, recs[0].rate_hz));
    }
    if (r.rate_si.size() != recs[0].rate_si.size()) {
      throw InputError(fmt::format("--in-motion: {} has {} samples but {} has {}: the recordings must be "
                                   "synchronous (same start and length; cut them to the common span)",
                                   r.source, r.rate_si.size(), recs[0].source, recs[0].rate_si.size()));
    }
    if (r.segments.size() > 1) {
      throw InputError(r.source + ": the recording is split at gaps; the in-motion analysis needs one unbroken "
                       "synchronous span per sensor");
    }
  }
}

nlohmann::json points_json(std::span<const DevPoint> points, double to_unit, bool full) {
  auto out = nlohmann::json::array();
  for (const auto& p : points) {
    nlohmann::json j{{"tau_s", p.tau_s}, {"adev", number(p.dev / to_unit)}, {"edf", number(p.edf)},
                     {"ci_low", number(p.ci_low / to_unit)}, {"ci_high", number(p.ci_high / to_unit)}};
    if (full) {
      j["m"] = p.m;
      j["n"] = p.n;
    }
    out.push_back(std::move(j));
  }
  return out;
}

}  // namespace

std::pair<double, std::string> g_sensitivity_unit(const Record& record) {
  // SI rad/s per m/s^2 -> deg/h per g for gyros; else the record's unit per m/s^2.
  if (is_gyro(record)) return {180.0 / std::numbers::pi * 3600.0 * kStandardGravity_m_s2, "deg/h/g"};
  return {1.0 / record.rate_unit.to_si, unit_label(record) + " per m/s^2"};
}

std::vector<DevPoint> fittable_points(std::span<const DevPoint> curve) {
  std::vector<DevPoint> out;
  for (const auto& p : curve) {
    if (std::isfinite(p.edf) && p.edf >= kMinFitEdf && p.dev > 0) out.push_back(p);
  }
  return out;
}

std::size_t effective_phase_count(std::span<const DevPoint> curve, std::size_t n_phase) {
  double ratio = 1.0;
  std::size_t max_m = 0;
  for (const auto& p : curve) {
    max_m = std::max(max_m, p.m);
    if (!std::isfinite(p.edf) || p.edf <= 0) continue;
    const Edf direct = edf(Estimator::oadev, p.alpha, p.m, n_phase);
    if (std::isfinite(direct.value) && direct.value > 0) ratio = std::min(ratio, p.edf / direct.value);
  }
  const auto n_eff = static_cast<std::size_t>(std::llround(ratio * static_cast<double>(n_phase)));
  return std::clamp(n_eff, std::min(n_phase, 2 * max_m + 2), n_phase);
}

InMotionUnit analyze_in_motion(const redundant::Geometry& geometry, std::vector<Record> recordings,
                               const redundant::InMotionOptions& options, const fit::FitOptions& fit_options,
                               const std::array<std::vector<double>, 3>& specific_force_m_s2) {
  check_unit(geometry, recordings);
  const bool force = !specific_force_m_s2[0].empty();
  if (force && specific_force_m_s2[0].size() != recordings[0].rate_si.size()) {
    throw InputError(fmt::format("--in-motion: the accelerometers have {} samples but the gyros {} (after any "
                                 "--skip or other preprocessing, which the accelerometers do not get): they must be "
                                 "synchronous; fix: drop the preprocessing or cut the files alike",
                                 specific_force_m_s2[0].size(), recordings[0].rate_si.size()));
  }
  InMotionUnit unit;
  unit.geometry = geometry;
  {
    std::vector<std::span<const double>> spans;
    for (const auto& r : recordings) spans.emplace_back(r.rate_si);
    std::vector<std::span<const double>> f;
    if (force) {
      for (const auto& c : specific_force_m_s2) f.emplace_back(c);
    }
    unit.result = redundant::in_motion_noise(geometry, spans, recordings[0].rate_hz, options, f);
  }
  const std::size_t n_phase = unit.result.samples + 1;
  for (std::size_t i = 0; i < recordings.size(); ++i) {
    InMotionSensor s;
    s.record = std::move(recordings[i]);
    s.record.rate_si = {};
    s.record.rate_si.shrink_to_fit();
    s.record.phase_si = {};
    s.record.phase_si.shrink_to_fit();
    s.identified = unit.result.identifiability.per_sensor;
    if (!s.identified) {
      s.reason = unit.result.identifiability.reason;
    } else {
      const auto curve = fittable_points(unit.result.sensors[i]);
      s.n_phase_effective = effective_phase_count(curve, n_phase);
      std::vector<std::string> warnings{fmt::format(
          "in-motion curve (parity space): fitted with the precision of a direct record of {} samples "
          "(the in-motion estimates' smallest EDF ratio), not the {} recorded", s.n_phase_effective - 1, n_phase - 1)};
      if (curve.size() < unit.result.sensors[i].size()) {
        warnings.push_back(fmt::format("{} of {} taus left out of the fit: their in-motion EDF is below {:g} (or the "
                                       "estimate is 0)", unit.result.sensors[i].size() - curve.size(),
                                       unit.result.sensors[i].size(), kMinFitEdf));
      }
      try {
        s.fit = fit_curve(s.record, curve, s.n_phase_effective, fit_options, warnings);
      } catch (const InputError& e) {
        s.reason = e.what();
      }
    }
    unit.sensors.push_back(std::move(s));
  }
  unit.notes = unit.result.notes;
  return unit;
}

Inflation coefficient_ratio(const Coefficient& in_motion, const Coefficient& at_rest, double level) {
  Inflation out;
  if (!in_motion.identified || !at_rest.identified) {
    out.reason = in_motion.identified ? "not identified at rest" : "not identified in motion";
    return out;
  }
  if (!(in_motion.ci_low > 0) || !(at_rest.ci_low > 0) || !(at_rest.value > 0) || !(in_motion.value > 0)) {
    out.reason = "an interval reaches 0: the ratio has no upper bound";
    return out;
  }
  const double z = std::sqrt(chi2_quantile(level, 1.0));
  const double sa = std::log(in_motion.ci_high / in_motion.ci_low) / (2 * z);
  const double sb = std::log(at_rest.ci_high / at_rest.ci_low) / (2 * z);
  const double s = std::hypot(sa, sb);
  out.available = true;
  out.ratio = in_motion.value / at_rest.value;
  out.ci_low = out.ratio * std::exp(-z * s);
  out.ci_high = out.ratio * std::exp(z * s);
  return out;
}

void compare_with_static(InMotionUnit& unit, std::vector<Record> static_recordings,
                         const fit::FitOptions& fit_options) {
  if (static_recordings.size() != unit.sensors.size()) {
    throw InputError(fmt::format("--static: {} recordings for the {} sensors; give each sensor's static recording, "
                                 "in the order of --in-motion", static_recordings.size(), unit.sensors.size()));
  }
  for (std::size_t i = 0; i < unit.sensors.size(); ++i) {
    auto& s = unit.sensors[i];
    s.static_fit = fit_channel(static_recordings[i], fit_options);
    Record description = std::move(static_recordings[i]);
    description.phase_si = {};
    description.rate_si = {};
    s.static_record = std::move(description);
    if (!s.fit) continue;
    for (int term : {fit::kN, fit::kB, fit::kK}) {
      s.inflation.emplace_back(term, coefficient_ratio(fit::coefficient(s.fit->coefficients, term),
                                                       fit::coefficient(s.static_fit->coefficients, term),
                                                       fit_options.level));
    }
  }
}

nlohmann::json in_motion_json(const InMotionUnit& unit, const fit::FitOptions& fit_options) {
  const auto& r = unit.result;
  const auto& id = r.identifiability;
  const Record& first = unit.sensors.front().record;
  const double to_unit = first.rate_unit.to_si;
  nlohmann::json doc;
  doc["geometry"] = unit.geometry.name;
  doc["rate_hz"] = r.rate_hz;
  doc["samples"] = r.samples;
  doc["unit"] = unit_label(first);
  doc["ci_level"] = r.ci_level;
  doc["identifiability"] = {{"sensors", id.sensors},
                            {"parity_channels", id.parity_channels},
                            {"equations", id.equations},
                            {"rank", id.rank},
                            {"per_sensor", id.per_sensor},
                            {"reason", id.per_sensor ? nlohmann::json(nullptr) : nlohmann::json(id.reason)},
                            {"unobservable", id.unobservable}};
  doc["common"] = {{"description", "sqrt(trace(C) / k): the weighted mean of the sensors' Allan variances, "
                                   "sum_i w_i a_i; each sensor's Allan deviation only if all have the same noise"},
                   {"weights", id.common_weights},
                   {"points", points_json(r.common, to_unit, false)}};
  const auto& lk = r.leakage;
  const char* convention =
      "minimum-norm errors D = V^T B: relative to the unit's best-fit frame (an error common to the unit, "
      "a distortion H X of its frame, does not reach the parity)";
  if (lk.removed) {
    std::vector<std::vector<double>> b(lk.coefficients.rows, std::vector<double>(lk.coefficients.cols));
    for (std::size_t j = 0; j < lk.coefficients.rows; ++j) {
      for (std::size_t a = 0; a < lk.coefficients.cols; ++a) b[j][a] = lk.coefficients(j, a);
    }
    doc["leakage"] = {{"removed", true},
                      {"coefficients", b},
                      {"motion_rms", number(lk.motion_rms_rad_s / to_unit)},
                      {"convention", convention},
                      {"timing", lk.timing},
                      {"g_sensitivity", lk.g_sensitivity_estimated}};
    if (lk.g_sensitivity_estimated) doc["leakage"]["specific_force_rms_m_s2"] = number(lk.specific_force_rms_m_s2);
  } else {
    doc["leakage"] = {{"removed", false}};
  }
  auto sensors = nlohmann::json::array();
  for (std::size_t i = 0; i < unit.sensors.size(); ++i) {
    const auto& s = unit.sensors[i];
    nlohmann::json j{{"source", s.record.source}, {"identified", s.identified}};
    if (lk.removed) {
      j["leakage"] = {{"scale_factor_ppm", number(lk.scale_factor_ppm[i])},
                      {"misalignment_mrad", number(lk.misalignment_mrad[i])}};
      if (lk.timing) j["leakage"]["time_offset_ms"] = number(lk.time_offset_ms[i]);
      if (lk.g_sensitivity_estimated) {
        const auto [factor, unit_name] = g_sensitivity_unit(s.record);
        nlohmann::json value = nlohmann::json::array();
        nlohmann::json se = nlohmann::json::array();
        for (std::size_t a = 0; a < 3; ++a) {
          value.push_back(number(lk.g_sensitivity_rad_s_per_m_s2[i][a] * factor));
          se.push_back(number(lk.g_sensitivity_se_rad_s_per_m_s2[i][a] * factor));
        }
        j["leakage"]["g_sensitivity"] = {{"value", value}, {"se", se}, {"unit", unit_name}, {"axes", "x, y, z of the body"}};
      }
    }
    if (!s.identified) {
      j["reason"] = s.reason;
    } else {
      j["curve"] = {{"estimator", "oadev in motion (parity space)"},
                    {"unit", unit_label(s.record)},
                    {"ci_level", r.ci_level},
                    {"points", points_json(r.sensors[i], s.record.rate_unit.to_si, true)}};
      if (s.static_fit) {
        j["static_fit"] = fit::report_json(record_info(*s.static_record), fit_options, *s.static_fit);
        nlohmann::json inflation = nlohmann::json::object();
        for (const auto& [term, ratio] : s.inflation) {
          inflation[fit::term_name(term)] =
              ratio.available ? nlohmann::json{{"ratio", ratio.ratio}, {"ci_low", ratio.ci_low}, {"ci_high", ratio.ci_high}}
                              : nlohmann::json{{"ratio", nullptr}, {"reason", ratio.reason}};
        }
        j["inflation"] = std::move(inflation);
      }
      if (s.fit) {
        j["fit"] = fit::report_json(record_info(s.record), fit_options, *s.fit);
      } else {
        j["fit"] = nullptr;
        j["fit_error"] = s.reason;
      }
    }
    sensors.push_back(std::move(j));
  }
  doc["sensors"] = std::move(sensors);
  doc["notes"] = unit.notes;
  return doc;
}

std::string in_motion_table(const InMotionUnit& unit) {
  const auto& r = unit.result;
  const auto& id = r.identifiability;
  const Record& first = unit.sensors.front().record;
  const std::string label = unit_label(first);
  const double to_unit = first.rate_unit.to_si;
  std::string out = fmt::format(
      "# in-motion noise (parity space): geometry {}, {} sensors, {} parity channels, {} Allan covariances, "
      "rank {}; {} samples at {:.9g} Hz; {:g}% intervals\n",
      unit.geometry.name, id.sensors, id.parity_channels, id.equations, id.rank, r.samples, r.rate_hz,
      100 * r.ci_level);
  if (!id.per_sensor) out += "# per-sensor curves not identified: " + id.reason + "\n";
  if (r.leakage.removed) {
    out += fmt::format("# motion leakage removed (fused motion RMS {:.6g} {}); per-sensor errors relative to the "
                       "unit's best-fit frame:\n", r.leakage.motion_rms_rad_s / to_unit, label);
    for (std::size_t i = 0; i < r.leakage.scale_factor_ppm.size(); ++i) {
      out += fmt::format("#   sensor {}: scale factor {:.6g} ppm, misalignment {:.6g} mrad", i + 1,
                         r.leakage.scale_factor_ppm[i], r.leakage.misalignment_mrad[i]);
      if (r.leakage.timing) out += fmt::format(", time offset {:.4g} ms", r.leakage.time_offset_ms[i]);
      if (r.leakage.g_sensitivity_estimated) {
        const auto [factor, unit_name] = g_sensitivity_unit(unit.sensors[i].record);
        const auto& g = r.leakage.g_sensitivity_rad_s_per_m_s2[i];
        const auto& se = r.leakage.g_sensitivity_se_rad_s_per_m_s2[i];
        out += fmt::format(", g-sensitivity ({:.4g}, {:.4g}, {:.4g}) +- ({:.2g}, {:.2g}, {:.2g}) {}", g[0] * factor,
                           g[1] * factor, g[2] * factor, se[0] * factor, se[1] * factor, se[2] * factor, unit_name);
      }
      out += "\n";
    }
  }
  const auto units = fit::coefficient_units(label);
  for (std::size_t i = 0; i < unit.sensors.size(); ++i) {
    const auto& s = unit.sensors[i];
    if (!s.identified) continue;
    out += fmt::format("\nsensor {} ({}):", i + 1, s.record.source);
    if (s.fit) {
      out += "\n";
      for (int term : {fit::kN, fit::kB, fit::kK}) {
        const auto& c = fit::coefficient(s.fit->coefficients, term);
        out += fmt::format("  {:<2} {:>13.6g} [{:.6g}, {:.6g}] {}{}\n", fit::term_name(term), c.value / to_unit,
                           c.ci_low / to_unit, c.ci_high / to_unit, units[static_cast<std::size_t>(term)],
                           c.identified ? "" : " (not identified)");
      }
      for (const auto& [term, ratio] : s.inflation) {
        out += ratio.available ? fmt::format("  {} in motion / at rest {:.4g} [{:.4g}, {:.4g}]\n", fit::term_name(term),
                                             ratio.ratio, ratio.ci_low, ratio.ci_high)
                               : fmt::format("  {} in motion / at rest: {}\n", fit::term_name(term), ratio.reason);
      }
    } else {
      out += " no fit: " + s.reason + "\n";
    }
    out += fmt::format("  {:>12} {:>13} {:>13} {:>13} {:>9}  ({})\n", "tau_s", "adev", "ci_low", "ci_high", "edf",
                       label);
    for (const auto& p : r.sensors[i]) {
      out += fmt::format("  {:>12.6g} {:>13.6g} {:>13.6g} {:>13.6g} {:>9.4g}\n", p.tau_s, p.dev / to_unit,
                         p.ci_low / to_unit, p.ci_high / to_unit, p.edf);
    }
  }
  out += fmt::format("\nweighted mean level sqrt(sum_i w_i a_i), w = [{:.4g}]{}:\n",
                     fmt::join(id.common_weights, ", "),
                     id.per_sensor ? "" : " (each sensor's level only if all have the same noise)");
  out += fmt::format("  {:>12} {:>13} {:>13} {:>13} {:>9}  ({})\n", "tau_s", "adev", "ci_low", "ci_high", "edf", label);
  for (const auto& p : r.common) {
    out += fmt::format("  {:>12.6g} {:>13.6g} {:>13.6g} {:>13.6g} {:>9.4g}\n", p.tau_s, p.dev / to_unit,
                       p.ci_low / to_unit, p.ci_high / to_unit, p.edf);
  }
  for (const auto& note : unit.notes) out += "# note: " + note + "\n";
  return out;
}

}  // namespace imunoise::study
