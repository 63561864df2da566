// The study pipeline and its report document.
#include "imunoise/study/study.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <span>
#include <thread>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "imunoise/error.hpp"
#include "imunoise/nav/imu_axes.hpp"
#include "imunoise/fit/extra_terms.hpp"
#include "imunoise/fit/gmwm.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/report.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "imunoise/redundant/report.hpp"
#include "imunoise/spec/exports.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/study/figures.hpp"
#include "imunoise/study/fit_stage.hpp"

namespace imunoise::study {
namespace {


// Allan deviation of term j (SI) at tau from its coefficient c (SI): the eq. 5 pieces.
double term_adev(int term, double c, double tau_s) {
  return std::sqrt(c * c * fit::term_basis(term, tau_s));
}

// Where a term's asymptote is labelled: the IEEE 952 read-off point (N at 1 s, K at 3 s,
// Q at sqrt(3) s, R at sqrt(2) s) when it lies on the curve, else the middle of the range
// where the term dominates the fit, else the middle of the curve.
double anchor_tau(int term, const fit::TermFit& t, double tau_lo, double tau_hi) {
  double tau = 0.0;
  switch (term) {
    case fit::kQ: tau = std::sqrt(3.0); break;
    case fit::kN: tau = 1.0; break;
    case fit::kK: tau = 3.0; break;
    case fit::kR: tau = std::sqrt(2.0); break;
    default: break;
  }
  if (t.tau_max_s > 0.0 && (tau < t.tau_min_s || tau > t.tau_max_s)) {
    tau = std::sqrt(t.tau_min_s * t.tau_max_s);
  }
  if (tau < tau_lo || tau > tau_hi) tau = std::sqrt(tau_lo * tau_hi);
  return tau;
}

// Figures group channels by this key: gyros, accelerometers, the rest.
std::string quantity_key(const Record& rec) {
  if (!rec.unit_given) return "unknown";
  if (rec.rate_unit.quantity == Quantity::angular_rate) return "angular_rate";
  if (rec.rate_unit.quantity == Quantity::acceleration) return "acceleration";
  return "unknown";
}

std::string short_number(double v) { return fmt::format("{:.3g}", v); }

// A sinusoid's Allan deviation A sin^2(x) / x, x = pi f tau, peaks where tan x = 2 x:
// x = 1.16556, tau = 0.37101 / f.
constexpr double kSinusoidPeakTimesPeriod = 0.37101;

// The fitted model and each identified term's asymptote, in the record's unit, on a dense
// log grid over the curve's taus. Asymptotes are cut where they leave the figure (a decade
// beyond the curve's range of values) so that they do not squash its scale.
nlohmann::json model_json(const Record& record, const Curve& oadev, const fit::FitResult& r,
                          const nlohmann::json& fit_doc) {
  const double f = record.rate_unit.to_si;
  double tau_lo = INFINITY, tau_hi = 0.0, dev_lo = INFINITY, dev_hi = 0.0;
  for (const auto& p : oadev.points) {
    if (!std::isfinite(p.dev) || p.dev <= 0.0) continue;
    tau_lo = std::min(tau_lo, p.tau_s);
    tau_hi = std::max(tau_hi, p.tau_s);
    dev_lo = std::min(dev_lo, p.dev);
    dev_hi = std::max(dev_hi, p.dev);
  }
  if (!(tau_hi > tau_lo)) return nullptr;
  // A sinusoid's lobes need a finer grid to be drawn as curves rather than zigzags.
  const bool has_sinusoid = r.coefficients.sinusoid.has_value();
  const int kPoints = has_sinusoid ? 320 : 80;
  std::vector<double> taus(static_cast<std::size_t>(kPoints));
  for (int i = 0; i < kPoints; ++i) {
    taus[static_cast<std::size_t>(i)] =
        tau_lo * std::pow(tau_hi / tau_lo, static_cast<double>(i) / (kPoints - 1));
  }
  const auto& c = r.coefficients;
  // gmwm: the curve of the model as fitted (a term kept by the selection but not significant
  // still shapes it), on the sample lattice where its AR1 forms are exact.
  const double tau0_s = 1.0 / record.rate_hz;
  const bool from_gmwm = r.gmwm && r.gmwm->status == fit::GmwmStatus::converged;
  if (from_gmwm) {
    for (double& tau : taus) tau = std::max(1.0, std::round(tau / tau0_s)) * tau0_s;
    taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
  }
  const auto sinusoid_shown = c.sinusoid && c.sinusoid->amplitude.identified && c.sinusoid->frequency_hz.identified;
  std::vector<double> total;
  for (double tau : taus) {
    double avar = 0.0;
    if (from_gmwm) {
      avar = fit::gmwm_model_avar(*r.gmwm, tau0_s, static_cast<std::size_t>(std::llround(tau / tau0_s)));
    } else {
      for (int j = 0; j < fit::kTermCount; ++j) {
        const double v = fit::coefficient(c, j).value;
        avar += v * v * fit::term_basis(j, tau);
      }
      for (const auto& gm : c.gauss_markov) {
        if (!identified(gm)) continue;
        const double g = gauss_markov_adev(gm.sigma.value, gm.correlation_time_s.value, tau);
        avar += g * g;
      }
      if (sinusoid_shown) {
        const double a = c.sinusoid->amplitude.value;
        avar += a * a * fit::sinusoid_basis(c.sinusoid->frequency_hz.value, tau);
      }
    }
    total.push_back(std::sqrt(avar) / f);
  }
  nlohmann::json terms = nlohmann::json::array();
  for (int j = 0; j < fit::kTermCount; ++j) {
    const auto& coefficient = fit::coefficient(c, j);
    if (!coefficient.identified || coefficient.value <= 0.0) continue;
    nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array();
    for (double tau : taus) {
      const double y = term_adev(j, coefficient.value, tau) / f;
      if (y < dev_lo / 10.0 || y > dev_hi * 10.0) continue;
      xs.push_back(tau);
      ys.push_back(y);
    }
    const double at = anchor_tau(j, r.terms[j], tau_lo, tau_hi);
    const auto& t = fit_doc["terms"][fit::term_name(j)];
    const auto& shown = t.contains("customary") ? t["customary"] : t;
    nlohmann::json term{
        {"symbol", fit::term_name(j)},
        {"label", fmt::format("{} = {} {}", fit::term_name(j),
                              short_number(shown["value"].get<double>()),
                              shown["unit"].get<std::string>())},
        {"tau_s", std::move(xs)},
        {"adev", std::move(ys)},
        {"anchor", {{"tau_s", at}, {"adev", term_adev(j, coefficient.value, at) / f}}}};
    terms.push_back(std::move(term));
  }
  // Each identified Gauss-Markov term's own curve (a bump, not an asymptote), anchored at its
  // peak (tau = 1.8926 T_c); GM1, GM2, ... by correlation time.
  int gm_index = 0;
  for (const auto& gm : c.gauss_markov) {
    if (!identified(gm)) continue;
    ++gm_index;
    const double sigma = gm.sigma.value, tc = gm.correlation_time_s.value;
    nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array();
    for (double tau : taus) {
      const double y = gauss_markov_adev(sigma, tc, tau) / f;
      if (y < dev_lo / 10.0 || y > dev_hi * 10.0) continue;
      xs.push_back(tau);
      ys.push_back(y);
    }
    const double at = std::clamp(kGaussMarkovPeakTau * tc, tau_lo, tau_hi);
    terms.push_back({{"symbol", fmt::format("GM{}", gm_index)},
                     {"label", fmt::format("GM{}: sigma = {} {}, T_c = {} s", gm_index, short_number(sigma / f),
                                           unit_label(record), short_number(tc))},
                     {"tau_s", std::move(xs)},
                     {"adev", std::move(ys)},
                     {"anchor", {{"tau_s", at}, {"adev", gauss_markov_adev(sigma, tc, at) / f}}}});
  }
  // The sinusoid's own curve: its Allan deviation A sin^2(pi f tau) / (pi f tau), peaking near
  // tau = 0.371 / f.
  if (sinusoid_shown) {
    const double a = c.sinusoid->amplitude.value, f0 = c.sinusoid->frequency_hz.value;
    nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array();
    for (double tau : taus) {
      const double y = a * std::sqrt(fit::sinusoid_basis(f0, tau)) / f;
      if (y < dev_lo / 10.0 || y > dev_hi * 10.0) continue;
      xs.push_back(tau);
      ys.push_back(y);
    }
    const double at = std::clamp(kSinusoidPeakTimesPeriod / f0, tau_lo, tau_hi);
    terms.push_back({{"symbol", "SIN"},
                     {"label", fmt::format("SIN: A = {} {}, f = {} Hz", short_number(a / f), unit_label(record),
                                           short_number(f0))},
                     {"tau_s", std::move(xs)},
                     {"adev", std::move(ys)},
                     {"anchor", {{"tau_s", at}, {"adev", a * std::sqrt(fit::sinusoid_basis(f0, at)) / f}}}});
  }
  return {{"unit", unit_label(record)},
          {"what", from_gmwm ? "fitted Allan deviation of the gmwm model, every term at its fitted value (also "
                               "those not significant), each identified power-law term's asymptote, each "
                               "Gauss-Markov term's curve and the sinusoid's"
                             : "fitted Allan deviation (eq. 5 with every Gauss-Markov term and the sinusoid), "
                               "each identified power-law term's asymptote, each Gauss-Markov term's curve and "
                               "the sinusoid's"},
          {"tau_s", taus},
          {"adev", total},
          {"terms", std::move(terms)}};
}

// The datasheet's limits drawn as Allan-deviation lines in the record's unit: N / sqrt(tau),
// the bias-instability floor sqrt(2 ln 2 / pi) B, and K sqrt(tau / 3).
nlohmann::json spec_limits_json(const Record& record, const Curve& oadev, const Spec& spec) {
  const double f = record.rate_unit.to_si;
  double tau_lo = INFINITY, tau_hi = 0.0;
  for (const auto& p : oadev.points) {
    tau_lo = std::min(tau_lo, p.tau_s);
    tau_hi = std::max(tau_hi, p.tau_s);
  }
  nlohmann::json lines = nlohmann::json::array();
  const auto add = [&](const std::optional<SpecTerm>& term, int j, const char* what) {
    if (!term || !std::isfinite(term->value_si)) return;
    const double limit = term->value_si * (1.0 + term->tolerance);
    nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array();
    for (int i = 0; i <= 20; ++i) {
      const double tau = tau_lo * std::pow(tau_hi / tau_lo, i / 20.0);
      xs.push_back(tau);
      ys.push_back(term_adev(j, limit, tau) / f);
    }
    lines.push_back({{"symbol", fit::term_name(j)},
                     {"label", fmt::format("datasheet {} {:g} {}", what, term->value,
                                           term->unit)},
                     {"tau_s", std::move(xs)},
                     {"adev", std::move(ys)}});
  };
  add(spec.random_walk, fit::kN, "N");
  add(spec.bias_instability, fit::kB, "B");
  add(spec.rate_random_walk, fit::kK, "K");
  return {{"spec", spec.name}, {"unit", unit_label(record)}, {"lines", std::move(lines)}};
}

// Kalibr keeps one value per sensor; a record with several axes is reduced by the rule below
// (the largest identified value over the axes: the filter is then never over-confident).
constexpr const char* kKalibrRule =
    "each key holds the largest identified value over the axes of that sensor type "
    "(conservative: the filter is never more confident than its noisiest axis)";

std::optional<NoiseCoefficients> combine_axes(const std::vector<const ChannelStudy*>& axes) {
  if (axes.empty()) return std::nullopt;
  NoiseCoefficients out = axes.front()->fit->coefficients;
  out.gauss_markov.clear();
  out.sinusoid.reset();
  for (int j = 0; j < fit::kTermCount; ++j) {
    Coefficient best = fit::coefficient(axes.front()->fit->coefficients, j);
    for (const auto* a : axes) {
      const auto& c = fit::coefficient(a->fit->coefficients, j);
      if (c.identified && (!best.identified || c.value > best.value)) best = c;
    }
    fit::coefficient(out, j) = best;
  }
  return out;
}

nlohmann::json kalibr_json(const Study& study) {
  std::vector<const ChannelStudy*> gyros, accels;
  std::vector<std::string> gyro_names, accel_names;
  for (const auto& ch : study.channels) {
    if (!ch.fit || !ch.record.unit_given) continue;
    if (ch.fit->coefficients.quantity == Quantity::angular_rate) {
      gyros.push_back(&ch);
      gyro_names.push_back(ch.record.name);
    } else {
      accels.push_back(&ch);
      accel_names.push_back(ch.record.name);
    }
  }
  if (gyros.empty()) {
    return {{"written", false},
            {"why", "no gyro channel with a unit and a fit (Kalibr's imu.yaml is written from "
                    "gyro axes, accelerometer axes added when present)"}};
  }
  const auto gyro = combine_axes(gyros);
  const auto accel = combine_axes(accels);
  std::string text = fmt::format("# imunoise study: {} gyro axes ({}), {} accelerometer axes{}\n",
                                 gyros.size(), fmt::join(gyro_names, ", "), accels.size(),
                                 accels.empty() ? "" : " (" + fmt::format("{}", fmt::join(accel_names, ", ")) + ")");
  text += std::string("# rule: ") + kKalibrRule + "\n";
  // What Kalibr has no field for, axis by axis (combine_axes drops it).
  std::vector<std::string> dropped;
  for (const auto* list : {&gyros, &accels}) {
    for (const auto* a : *list) {
      for (const auto& line : not_carried(a->fit->coefficients, "Kalibr")) {
        dropped.push_back(a->record.name + ": " + line);
        text += "# " + dropped.back() + "\n";
      }
    }
  }
  text += kalibr_imu_yaml(*gyro, accel ? &*accel : nullptr, study.channels.front().record.rate_hz,
                          study.options.kalibr_inflation, study.options.kalibr_topic);
  return {{"written", true},
          {"rule", kKalibrRule},
          {"gyro_axes", gyro_names},
          {"accelerometer_axes", accel_names},
          {"complete", !accels.empty()},
          {"not_carried", dropped},
          {"text", text}};
}


// The dynamic Allan variance in the report: deviations (not variances) in the record's unit,
// null where a window holds too few terms at a tau.
nlohmann::json davar_json(const Record& record, const preprocess::DavarResult& d) {
  const double f = record.rate_unit.to_si;
  const auto dev = [f](double avar) {
    return std::isfinite(avar) && avar > 0.0 ? nlohmann::json(std::sqrt(avar) / f) : nlohmann::json(nullptr);
  };
  nlohmann::json adev = nlohmann::json::array(), flagged = nlohmann::json::array();
  std::size_t n_flagged = 0;
  for (std::size_t w = 0; w < d.avar.size(); ++w) {
    nlohmann::json row = nlohmann::json::array(), flags = nlohmann::json::array();
    for (std::size_t j = 0; j < d.avar[w].size(); ++j) {
      row.push_back(dev(d.avar[w][j]));
      flags.push_back(static_cast<bool>(d.flagged[w][j]));
    }
    adev.push_back(std::move(row));
    flagged.push_back(std::move(flags));
    n_flagged += d.window_flagged[w] ? 1 : 0;
  }
  nlohmann::json reference = nlohmann::json::array();
  for (const double v : d.reference_avar) reference.push_back(dev(v));
  return {{"unit", unit_label(record)},
          {"window_s", d.window_s},
          {"step_s", d.step_s},
          {"window_start_s", d.window_start_s},
          {"tau_s", d.tau_s},
          {"adev", std::move(adev)},
          {"reference_adev", std::move(reference)},
          {"flagged", std::move(flagged)},
          {"window_flagged", std::vector<bool>(d.window_flagged.begin(), d.window_flagged.end())},
          {"n_windows", d.avar.size()},
          {"n_flagged_windows", n_flagged},
          {"stationary", d.stationary},
          {"change_times_s", d.change_times_s},
          {"suggested_skip_s", d.suggested_skip_s},
          {"rule", "a window is flagged at a tau when its Allan variance over the median of all "
                   "windows lies outside the chi-squared band of its degrees of freedom "
                   "(Bonferroni over windows and taus: a stationary record is called "
                   "non-stationary with probability < 0.001); stationary: no window flagged"}};
}

// The channels of one sensor kind on the axes (nav/imu_axes.hpp).
std::array<const ChannelStudy*, 3> on_axes(const std::vector<const ChannelStudy*>& channels) {
  std::vector<std::string> names;
  for (const ChannelStudy* ch : channels) names.push_back(ch->record.name);
  const auto index = nav::channels_on_axes(names);
  std::array<const ChannelStudy*, 3> axes{};
  for (std::size_t i = 0; i < 3; ++i) axes[i] = index[i] >= 0 ? channels[static_cast<std::size_t>(index[i])] : nullptr;
  return axes;
}

nav::NavOptions nav_options(const StudyOptions& options, const NoiseCoefficients& c);

// The whole IMU (study.hpp, Study::imu).
void study_imu(Study& study) {
  std::vector<const ChannelStudy*> gyros, accels;
  std::vector<std::string> unitless;
  for (const auto& ch : study.channels) {
    if (ch.fit && !ch.record.unit_given) unitless.push_back(ch.record.name);
    if (!ch.fit || !ch.record.unit_given) continue;
    if (ch.fit->coefficients.quantity == Quantity::angular_rate) gyros.push_back(&ch);
    if (ch.fit->coefficients.quantity == Quantity::acceleration) accels.push_back(&ch);
  }
  if (gyros.empty() || accels.empty()) {
    if (!unitless.empty() && (!gyros.empty() || !accels.empty())) {
      study.notes.push_back(fmt::format("{} without a unit: left out of the whole IMU's navigation error (give "
                                        "--units, e.g. deg/s for gyros and g or m/s^2 for accelerometers)",
                                        fmt::join(unitless, ", ")));
    }
    return;
  }
  const auto g = on_axes(gyros), a = on_axes(accels);
  nav::NavOptions o = nav_options(study.options, NoiseCoefficients{});
  Study::ImuNavigation imu;
  // The navigation run is as long as the shortest record measured.
  auto duration_s = [](const auto* ch) { return static_cast<double>(ch->record.n_samples) / ch->record.rate_hz; };
  for (const auto* ch : gyros) o.measured_s = o.measured_s == 0.0 ? duration_s(ch) : std::min(o.measured_s, duration_s(ch));
  for (const auto* ch : accels) o.measured_s = std::min(o.measured_s, duration_s(ch));
  for (std::size_t i = 0; i < 3; ++i) {
    o.axes[i] = nav::GyroAxisNoise{};
    if (g[i]) {
      o.axes[i].coefficients = g[i]->fit->coefficients;
      imu.gyro_channels[i] = g[i]->record.name;
    }
    if (a[i]) {
      o.accel_axes[i].coefficients = a[i]->fit->coefficients;
      imu.accel_channels[i] = a[i]->record.name;
    }
  }
  // The paper's eq. 6 is a gyro formula for one axis: the whole IMU is told by the physical models.
  std::vector<nav::Model> models;
  for (nav::Model m : o.models) {
    if (m != nav::Model::paper) models.push_back(m);
  }
  if (models.empty()) models = {nav::Model::schuler, nav::Model::covariance};
  o.models = models;
  try {
    imu.result = nav::navigation_error(o);
    study.imu = std::move(imu);
  } catch (const InputError& e) {
    study.notes.push_back(std::string("whole-IMU navigation error not computed: ") + e.what());
  }
}

nav::NavOptions nav_options(const StudyOptions& options, const NoiseCoefficients& c) {
  nav::NavOptions o;
  for (auto& axis : o.axes) axis.coefficients = c;  // the same gyro on every axis (eq. 6)
  o.duration_s = options.nav_hours * 3600.0;
  o.step_s = o.duration_s >= 600.0 ? 60.0 : o.duration_s / 10.0;
  o.dt_s = o.step_s >= 1.0 ? 1.0 : o.step_s;
  o.latitude_rad = options.nav_latitude_deg * std::numbers::pi / 180.0;
  o.models = nav::parse_models(options.nav_models);
  return o;
}

// Fault detection on the recorded data (the redundant module's detector). The rates are the
// phase's first differences: the offset phase_from_rate removed is constant per sensor, and the
// detector tests only changes of the parity against its reference window.
void detect_faults(Study& study, const redundant::Analysis& analysis,
                   const std::vector<const ChannelStudy*>& used, double rate_hz, unsigned threads) {
  const double tau0_s = 1.0 / rate_hz;
  std::vector<std::vector<double>> rates(used.size());
  std::vector<std::span<const double>> spans;
  for (std::size_t i = 0; i < used.size(); ++i) {
    const auto& phase = used[i]->record.phase_si;
    rates[i].resize(phase.size() - 1);
    for (std::size_t k = 0; k + 1 < phase.size(); ++k) rates[i][k] = (phase[k + 1] - phase[k]) / tau0_s;
    spans.emplace_back(rates[i]);
  }
  redundant::FusionOptions options;
  options.detect = true;
  options.parity = false;
  options.threads = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
  try {
    const auto fused = redundant::fuse_records(analysis, spans, rate_hz, options);
    if (fused.detection) study.redundant->detection = std::move(fused.detection);
  } catch (const InputError& e) {
    study.notes.push_back(std::string("redundant unit: fault detection not run on the record: ") + e.what());
  }
}

// The redundant unit: the channels are its sensors, in order. The analysis (fusion matrix,
// fused axes' noise predicted from the sensors' fits, parity, detection design) comes from the
// redundant module; the fused axes' curves are measured here by applying the fusion matrix to
// the samples (fusion is linear, so fusing the angles fuses the rates).
void study_redundant(Study& study, const CurveOptions& curve_options) {
  const auto geometry = redundant::make_geometry(study.options.geometry);
  std::vector<redundant::SensorModel> sensors;
  std::vector<const ChannelStudy*> used;
  for (const auto& ch : study.channels) {
    if (!ch.fit || ch.fit->coefficients.quantity != Quantity::angular_rate) continue;
    sensors.push_back({ch.record.name, ch.fit->coefficients});
    used.push_back(&ch);
  }
  if (sensors.size() != geometry.size()) {
    study.notes.push_back(fmt::format(
        "redundant unit ({}): it has {} sensors but {} gyro channels were fitted; no fusion "
        "(give one channel per sensor, in the geometry's order)",
        geometry.name, geometry.size(), sensors.size()));
    return;
  }
  const auto analysis = redundant::analyze_unit(geometry, sensors);
  study.redundant = Study::Redundant{analysis, used.front()->record.rate_unit, std::nullopt};
  Record fused;
  fused.rate_hz = used.front()->record.rate_hz;
  fused.rate_unit = used.front()->record.rate_unit;
  fused.unit_given = true;
  const std::size_t n = used.front()->record.phase_si.size();
  for (const auto* ch : used) {
    if (ch->record.phase_si.size() != n) {
      study.notes.push_back("redundant unit: the channels differ in length; fused axes not measured");
      return;
    }
  }
  fused.n_samples = used.front()->record.n_samples;
  detect_faults(study, analysis, used, fused.rate_hz, curve_options.threads);
  CurveOptions co = curve_options;
  co.estimators = {Estimator::oadev};
  const char* names[3] = {"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    fused.name = std::string("fused ") + names[axis];
    fused.source = "fusion of " + std::to_string(used.size()) + " gyros (" + geometry.name + ")";
    fused.phase_si.assign(n, 0.0);
    for (std::size_t i = 0; i < used.size(); ++i) {
      const double g = analysis.fusion(axis, i);
      const auto& phase = used[i]->record.phase_si;
      for (std::size_t k = 0; k < n; ++k) fused.phase_si[k] += g * phase[k];
    }
    auto curves = compute_curves(fused, co);
    curves.front().label = fused.name;
    study.fused_curves.push_back(std::move(curves.front()));
  }
  fused.phase_si.clear();
  fused.phase_si.shrink_to_fit();
  fused.name = "fused";
  study.fused_record = std::move(fused);
}

}  // namespace

std::string_view version() { return "0.1.0"; }

void check_compatible(const std::vector<Record>& records) {
  for (std::size_t i = 1; i < records.size(); ++i) {
    const auto& a = records.front();
    const auto& b = records[i];
    if (std::abs(a.rate_hz - b.rate_hz) > 1e-6 * a.rate_hz) {
      throw InputError(fmt::format(
          "{} is sampled at {:.9g} Hz but {} at {:.9g} Hz: a study compares and fuses channels "
          "sampled together; fix: resample to one rate, or analyze them separately",
          b.name, b.rate_hz, a.name, a.rate_hz));
    }
    if (a.unit_given != b.unit_given) {
      throw InputError(fmt::format(
          "{} has a unit ({}) but {} has none: fix: give --units for every channel",
          a.unit_given ? a.name : b.name, a.unit_given ? a.rate_unit.name : b.rate_unit.name,
          a.unit_given ? b.name : a.name));
    }
  }
  for (std::size_t i = 0; i < records.size(); ++i) {
    for (std::size_t k = i + 1; k < records.size(); ++k) {
      const auto& a = records[i];
      const auto& b = records[k];
      if (a.unit_given && a.rate_unit.quantity == b.rate_unit.quantity &&
          a.rate_unit.name != b.rate_unit.name) {
        throw InputError(fmt::format(
            "{} is in {} but {} in {}: channels of one kind must share a unit to be compared; "
            "fix: give the same --units (with --scale) for both",
            a.name, a.rate_unit.name, b.name, b.rate_unit.name));
      }
      if (a.name == b.name) {
        throw InputError("two channels are both called '" + a.name +
                         "'; fix: name the columns differently (--names)");
      }
    }
  }
}

Study run_study(std::vector<Record> records, const StudyOptions& options,
                std::vector<FailedInput> failed, const Progress& progress) {
  if (records.empty()) {
    throw InputError(failed.empty() ? std::string("no channels to study")
                                    : "no input could be read: " + failed.front().source + ": " +
                                          failed.front().error);
  }
  check_compatible(records);
  std::string why;
  if (!options.fit.IsValid(&why)) throw InputError("fit options: " + why);
  if (!(options.nav_hours > 0.0)) throw InputError("--nav-hours must be positive");
  if (!options.geometry.empty()) {
    // One channel per sensor of the unit, or the fusion is meaningless: say so before the work.
    const auto geometry = redundant::make_geometry(options.geometry);
    const std::size_t given = records.size() + failed.size();
    if (given != geometry.size()) {
      throw InputError(fmt::format("--geometry {}: the unit has {} sensors but {} channel(s) were given; "
                                   "fix: give one gyro channel per sensor, in the geometry's order, "
                                   "or drop --geometry", options.geometry, geometry.size(), given));
    }
  }
  Study study;
  study.options = options;
  study.failed_inputs = std::move(failed);
  CurveOptions curve_options = options.curves;
  if (std::find(curve_options.estimators.begin(), curve_options.estimators.end(),
                Estimator::oadev) == curve_options.estimators.end()) {
    curve_options.estimators.insert(curve_options.estimators.begin(), Estimator::oadev);
  }
  const double n = static_cast<double>(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    ChannelStudy ch;
    ch.record = std::move(records[i]);
    const auto report = [&](const char* stage, double part) {
      if (progress) {
        progress(fmt::format("{}: {}", ch.record.name, stage), (static_cast<double>(i) + part) / n);
      }
    };
    try {
      report("deviation curves", 0.0);
      ch.curves = compute_curves(ch.record, curve_options,
                                 [&](const std::string& note) { ch.warnings.push_back(note); });
      report("noise-model fit", 0.5);
      ch.fit = fit_channel(ch.record, options.fit, options.fit_grid);
      for (const auto& w : ch.fit->summary.warnings) ch.warnings.push_back(w);
      if (options.spec) ch.comparison = compare(ch.fit->coefficients, *options.spec);
    } catch (const InputError& e) {
      if (!options.keep_going) throw;
      ch.error = e.what();
    }
    if (ch.fit && ch.fit->coefficients.quantity == Quantity::angular_rate && ch.record.unit_given) {
      report("navigation error", 0.8);
      try {
        ch.nav = navigation(ch.fit->coefficients, options);
      } catch (const InputError& e) {
        ch.warnings.push_back(std::string("navigation error not computed: ") + e.what());
      }
    }
    // The samples are kept only when the redundant unit's axes are fused from them.
    if (options.geometry.empty()) {
      ch.record.phase_si.clear();
      ch.record.phase_si.shrink_to_fit();
    }
    study.channels.push_back(std::move(ch));
  }
  if (!options.geometry.empty()) {
    if (progress) progress("redundant unit: fusion and fault detection", 0.95);
    study_redundant(study, curve_options);
  }
  for (auto& ch : study.channels) {
    ch.record.phase_si.clear();
    ch.record.phase_si.shrink_to_fit();
  }
  study_imu(study);
  if (progress) progress("done", 1.0);
  return study;
}

nav::NavResult navigation(const NoiseCoefficients& c, const StudyOptions& options) {
  return nav::navigation_error(nav_options(options, c));
}

nlohmann::json study_json(const Study& study) {
  nlohmann::json doc;
  doc["title"] = study.options.title;
  doc["version"] = std::string(version());
  nlohmann::json inputs = nlohmann::json::array();
  for (const auto& ch : study.channels) {
    inputs.push_back({{"source", ch.record.source}, {"channel", ch.record.name},
                      {"status", ch.error.empty() ? "ok" : "failed"},
                      {"error", ch.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(ch.error)}});
  }
  for (const auto& f : study.failed_inputs) {
    inputs.push_back({{"source", f.source}, {"channel", nullptr}, {"status", "unreadable"},
                      {"error", f.error}});
  }
  doc["inputs"] = std::move(inputs);
  const auto& o = study.options;
  doc["options"] = {{"fit_method", fit::method_name(o.fit.method)},
                    {"fit_level", o.fit.level},
                    {"curve_ci_level", o.curves.ci_level},
                    {"spec", o.spec ? nlohmann::json(o.spec->name) : nlohmann::json(nullptr)},
                    {"nav_hours", o.nav_hours},
                    {"nav_latitude_deg", o.nav_latitude_deg},
                    {"nav_models", o.nav_models},
                    {"geometry", o.geometry.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.geometry)}};
  nlohmann::json channels = nlohmann::json::array();
  for (const auto& ch : study.channels) {
    const auto& rec = ch.record;
    nlohmann::json c{{"name", rec.name},
                     {"source", rec.source},
                     {"unit", unit_label(rec)},
                     {"quantity", quantity_key(rec)},
                     {"rate_hz", rec.rate_hz},
                     {"n_samples", rec.n_samples},
                     {"duration_s", static_cast<double>(rec.n_samples) / rec.rate_hz}};
    if (!ch.error.empty()) c["error"] = ch.error;
    // Where the channel came from and what preprocessing removed, when there is more to say
    // than the source.
    if (!rec.channel.empty()) {
      c["recording"] = {{"format", rec.format}, {"stream", rec.stream}, {"channel", rec.channel}};
    }
    if (!rec.preprocessing.empty()) c["preprocessing"] = rec.preprocessing;
    c["curves"] = curves_json(rec, ch.curves);
    if (ch.fit) {
      auto fit_doc = fit::report_json(record_info(rec), o.fit, *ch.fit);
      const Curve* oadev_curve = nullptr;
      for (const auto& curve : ch.curves) {
        if (curve.label == "oadev") oadev_curve = &curve;
      }
      if (oadev_curve) {
        c["model"] = model_json(rec, *oadev_curve, *ch.fit, fit_doc);
        if (o.spec) c["spec_limits"] = spec_limits_json(rec, *oadev_curve, *o.spec);
      }
      c["fit"] = std::move(fit_doc);
    } else {
      c["fit"] = nullptr;
    }
    c["spec_comparison"] = ch.comparison ? comparison_json(*ch.comparison) : nlohmann::json(nullptr);
    c["nav"] = ch.nav ? nav::report_json(*ch.nav) : nlohmann::json(nullptr);
    c["davar"] = rec.davar ? davar_json(rec, *rec.davar) : nlohmann::json(nullptr);
    c["warnings"] = ch.warnings;
    channels.push_back(std::move(c));
  }
  doc["channels"] = std::move(channels);
  doc["redundant"] = nullptr;
  if (study.redundant) {
    const auto& r = *study.redundant;
    doc["redundant"] = redundant::report_json(r.analysis, r.unit, r.detection ? &*r.detection : nullptr);
  }
  if (study.redundant && !study.fused_curves.empty()) {
    doc["redundant"]["fused_curves"] = curves_json(study.fused_record, study.fused_curves);
  }
  doc["imu_nav"] = nullptr;
  if (study.imu) {
    doc["imu_nav"] = {{"gyro_channels", study.imu->gyro_channels},
                      {"accel_channels", study.imu->accel_channels},
                      {"nav", nav::report_json(study.imu->result)}};
  }
  doc["kalibr"] = kalibr_json(study);
  doc["notes"] = study.notes;
  doc["figures"] = build_figures(doc);
  return doc;
}

}  // namespace imunoise::study
