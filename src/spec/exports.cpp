#include "imunoise/spec/exports.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise {

std::string round_trip_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  // YAML 1.1 (PyYAML) reads "3e-05" and "200" as a string and an int: give a '.' always.
  const auto exponent = text.find_first_of("eE");
  const auto mantissa_end = exponent == std::string::npos ? text.size() : exponent;
  if (text.find('.') == std::string::npos) text.insert(mantissa_end, ".0");
  return text;
}

double gauss_markov_adev(double sigma, double correlation_time_s, double tau_s) {
  const double x = tau_s / correlation_time_s;
  const double bracket = 1.0 - (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x)) / (2.0 * x);
  return std::sqrt(2.0 * sigma * sigma / x * bracket);
}

std::vector<std::string> not_carried(const NoiseCoefficients& c, std::string_view format) {
  std::vector<std::string> out;
  const std::string unit = c.quantity == Quantity::acceleration ? "m/s^2" : "rad/s";
  std::string terms;
  int count = 0;
  for (const auto& g : c.gauss_markov) {
    if (!identified(g)) continue;
    terms += fmt::format("{}sigma {:.4g} {}, T_c {:.4g} s", count > 0 ? "; " : "", g.sigma.value, unit,
                         g.correlation_time_s.value);
    ++count;
  }
  if (count > 0) {
    out.push_back(fmt::format("{} Gauss-Markov term{} ({}) not carried: {} has no Gauss-Markov "
                              "parameter; the Kalman-filter JSON export has one state per term",
                              count, count > 1 ? "s" : "", terms, format));
  }
  if (c.sinusoid && c.sinusoid->amplitude.identified && c.sinusoid->amplitude.value > 0.0) {
    out.push_back(fmt::format("sinusoid (amplitude {:.4g} {}, {:.4g} Hz) not carried: {} has no "
                              "sinusoid parameter",
                              c.sinusoid->amplitude.value, unit, c.sinusoid->frequency_hz.value, format));
  }
  return out;
}

namespace {

void check_rate(double rate_hz, std::string_view what) {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    throw InputError(std::string(what) + ": sample rate " + round_trip_number(rate_hz) +
                     " Hz is not positive; fix: pass the IMU's sample rate (--rate HZ)");
  }
}

struct KalibrUnits {
  const char* sensor;        // "gyroscope" / "accelerometer"
  const char* density_unit;  // rad/s/sqrt(Hz)
  const char* walk_unit;     // rad/s^2/sqrt(Hz)
  const char* rate_unit;     // rad/s
  const char* customary_n;   // deg/sqrt(h)
  double customary_n_to_si;
  const char* customary_k;
  double customary_k_to_si;
};

constexpr KalibrUnits kGyroUnits{"gyroscope",     "rad/s/sqrt(Hz)",      "rad/s^2/sqrt(Hz)",
                                 "rad/s",         "deg/sqrt(h)",         customary_gyro_N.to_si,
                                 "deg/h/sqrt(h)", customary_gyro_K.to_si};
constexpr KalibrUnits kAccelUnits{"accelerometer",  "m/s^2/sqrt(Hz)",
                                  "m/s^3/sqrt(Hz)", "m/s^2",
                                  "m/s/sqrt(h)",    1.0 / units::sqrt_h_to_sqrt_s,
                                  "m/s^2/sqrt(h)",  1.0 / units::sqrt_h_to_sqrt_s};

// Six significant digits, for comments meant for people (the exact values are in the keys).
std::string readable(double value) { return fmt::format("{:.6g}", value); }

std::string ci_text(const Coefficient& c, double to_unit, double level) {
  if (!std::isfinite(c.ci_low) || !std::isfinite(c.ci_high)) return "";
  return " [" + std::to_string(static_cast<int>(std::lround(level * 100))) + "% CI " +
         readable(c.ci_low / to_unit) + " .. " + readable(c.ci_high / to_unit) + "]";
}

void raw_comment(std::string& out, const char* key, char symbol, const Coefficient& c,
                 const char* unit, const char* customary, double customary_to_si, double level) {
  out += "#   " + std::string(key) + " raw " + symbol + " = ";
  if (!c.identified) {
    out += "not identified" + (c.note.empty() ? std::string() : " (" + c.note + ")") + "\n";
    return;
  }
  out += round_trip_number(c.value) + " " + unit + ci_text(c, 1.0, level) + " = " +
         readable(c.value / customary_to_si) + " " + customary + "\n";
}

void value_line(std::string& out, const std::string& key, const Coefficient& c, double inflation,
                const char* unit, char symbol) {
  if (c.identified && std::isfinite(c.value) && c.value > 0.0) {
    out += key + ": " + round_trip_number(c.value * inflation) + "  # " + unit + " = " + symbol +
           (inflation != 1.0 ? " x inflation" : "") + "\n";
  } else {
    out += "# " + key + ": <FILL IN>  # " + unit + " -- NOT IDENTIFIED by imunoise (" + symbol +
           " absent from the record" + (c.note.empty() ? "" : ": " + c.note) +
           "); Kalibr needs a value: supply one from a longer record or the datasheet\n";
  }
}

void sensor_block(std::string& out, const NoiseCoefficients& c, const KalibrUnits& u,
                  double inflation) {
  out += "# " + std::string(u.sensor) + " (measured by imunoise, " +
         (inflation == 1.0 ? std::string("no inflation")
                           : "inflated x" + round_trip_number(inflation)) +
         "):\n";
  const std::string prefix = u.sensor;
  raw_comment(out, (prefix + "_noise_density").c_str(), 'N', c.random_walk, u.density_unit,
              u.customary_n, u.customary_n_to_si, c.confidence_level);
  raw_comment(out, (prefix + "_random_walk").c_str(), 'K', c.rate_random_walk, u.walk_unit,
              u.customary_k, u.customary_k_to_si, c.confidence_level);
  if (c.bias_instability.identified) {
    out += "#   (bias instability B = " + readable(c.bias_instability.value) + " " + u.rate_unit +
           " is not a Kalibr parameter; see the Kalman-filter JSON export)\n";
  }
  for (const auto& line : not_carried(c, "Kalibr")) out += "#   (" + line + ")\n";
  value_line(out, prefix + "_noise_density", c.random_walk, inflation, u.density_unit, 'N');
  value_line(out, prefix + "_random_walk", c.rate_random_walk, inflation, u.walk_unit, 'K');
}

}  // namespace

std::string kalibr_imu_yaml(const NoiseCoefficients& gyro, const NoiseCoefficients* accel,
                            double rate_hz, double inflation, std::string_view topic) {
  if (gyro.quantity != Quantity::angular_rate) {
    throw InputError("Kalibr export: the gyroscope coefficients are of " +
                     std::string(quantity_name(gyro.quantity)) +
                     "; fix: export from a gyro fit (rate units deg/s, rad/s, ...)");
  }
  if (accel != nullptr && accel->quantity != Quantity::acceleration) {
    throw InputError("Kalibr export: the accelerometer coefficients are of " +
                     std::string(quantity_name(accel->quantity)) +
                     "; fix: export from an accelerometer fit (rate units g, m/s^2, ...)");
  }
  check_rate(rate_hz, "Kalibr export");
  if (!(std::isfinite(inflation) && inflation > 0.0)) {
    throw InputError("Kalibr export: inflation factor " + round_trip_number(inflation) +
                     " is not positive; fix: pass --inflation X with X > 0 (1 = measured values)");
  }
  const std::string rostopic = topic.empty() ? std::string("/imu0") : std::string(topic);

  std::string out;
  out +=
      "# IMU noise model for Kalibr (https://github.com/ethz-asl/kalibr/wiki/IMU-Noise-Model),\n"
      "# written by imunoise 0.1.0 from an Allan-variance fit (IEEE Std 952 noise model).\n"
      "# Continuous-time values: *_noise_density = N (white noise, sqrt of the two-sided PSD),\n"
      "# *_random_walk = K (bias random walk). Discrete equivalents at update_rate f:\n"
      "# sigma_d = noise_density * sqrt(f), sigma_bd = random_walk / sqrt(f).\n";
  out += "# imunoise inflation factor: " + round_trip_number(inflation) +
         (inflation == 1.0
              ? " (values are the measured ones)\n"
              : " (every value below = measured value x " + round_trip_number(inflation) + ")\n");
  out += "\n";
  sensor_block(out, gyro, kGyroUnits, inflation);
  out += "\n";
  if (accel != nullptr) {
    sensor_block(out, *accel, kAccelUnits, inflation);
  } else {
    out +=
        "# accelerometer: NOT MEASURED -- imunoise had no accelerometer record and does not\n"
        "# invent numbers. Kalibr needs both keys: fill them in from an accelerometer analysis\n"
        "# (imunoise fit of each accelerometer axis) or the datasheet, then uncomment.\n"
        "# accelerometer_noise_density: <FILL IN>  # m/s^2/sqrt(Hz)\n"
        "# accelerometer_random_walk: <FILL IN>  # m/s^3/sqrt(Hz)\n";
  }
  out += "\n";
  out += "update_rate: " + round_trip_number(rate_hz) + "  # Hz\n";
  out += "rostopic: " + rostopic + "\n";
  return out;
}

namespace {

nlohmann::json quantity_json(double value, std::string unit) {
  return {{"value", std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr)},
          {"unit", std::move(unit)}};
}

nlohmann::json coefficient_json(const Coefficient& c, const std::string& unit) {
  nlohmann::json j = quantity_json(c.identified ? c.value : std::nan(""), unit);
  j["ci_low"] = std::isfinite(c.ci_low) ? nlohmann::json(c.ci_low) : nlohmann::json(nullptr);
  j["ci_high"] = std::isfinite(c.ci_high) ? nlohmann::json(c.ci_high) : nlohmann::json(nullptr);
  j["identified"] = c.identified;
  if (!c.note.empty()) j["note"] = c.note;
  return j;
}

// The discrete first-order Gauss-Markov state of sigma (x) and T_c (s) at the sample period dt.
void add_gauss_markov_state(nlohmann::json& b, double sigma, double tc, double dt, const std::string& x,
                            const std::string& psd_walk) {
  b["sigma"] = quantity_json(sigma, x);
  b["correlation_time"] = quantity_json(tc, "s");
  const bool full = std::isfinite(sigma) && std::isfinite(tc) && tc > 0.0;
  const double nan = std::nan("");
  const double phi = full ? std::exp(-dt / tc) : nan;
  b["driving_psd"] = quantity_json(full ? 2.0 * sigma * sigma / tc : nan, psd_walk);
  b["discrete_phi"] = quantity_json(phi, "1");
  b["discrete_phi"]["formula"] = "exp(-dt / T_c)";
  b["discrete_sigma"] = quantity_json(full ? sigma * std::sqrt(1.0 - phi * phi) : nan, x);
  b["discrete_sigma"]["formula"] = "sigma sqrt(1 - phi^2)";
}

}  // namespace

nlohmann::json kalman_parameters(const NoiseCoefficients& c, double rate_hz,
                                 std::optional<double> bias_floor_tau_s) {
  if (c.quantity != Quantity::angular_rate && c.quantity != Quantity::acceleration) {
    throw InputError("Kalman-filter export: coefficients of " +
                     std::string(quantity_name(c.quantity)) +
                     " are not supported; fix: export a gyro or accelerometer fit");
  }
  check_rate(rate_hz, "Kalman-filter export");
  if (bias_floor_tau_s && !(std::isfinite(*bias_floor_tau_s) && *bias_floor_tau_s > 0.0)) {
    throw InputError("Kalman-filter export: averaging time of the Allan floor " +
                     round_trip_number(*bias_floor_tau_s) +
                     " s is not positive; fix: give the "
                     "tau (s) at the bottom of the Allan-deviation curve");
  }
  const bool gyro = c.quantity == Quantity::angular_rate;
  const double dt = 1.0 / rate_hz;
  // Units with the state = the sensor's rate x (rad/s or m/s^2); "a" is its integral unit.
  const std::string x = gyro ? "rad/s" : "m/s^2";
  const std::string psd_white = gyro ? "rad^2/s" : "m^2/s^3";   // x^2/Hz
  const std::string psd_walk = gyro ? "rad^2/s^3" : "m^2/s^5";  // x^2/s
  const std::string n_unit = gyro ? "rad/sqrt(s)" : "m/s/sqrt(s)";
  const std::string k_unit = gyro ? "rad/s/sqrt(s)" : "m/s^2/sqrt(s)";

  nlohmann::json j;
  j["sensor"] = gyro ? "gyroscope" : "accelerometer";
  j["state"] = "sensor rate error, in " + x;
  j["rate_hz"] = rate_hz;
  j["dt_s"] = dt;
  j["conventions"] =
      "continuous white noise w(t) with E[w(t) w(t+s)] = psd * delta(s) (two-sided PSD, "
      "psd = N^2, as Kalibr's noise density squared); discrete values for the sample period dt";
  // The filter's Gauss-Markov states, one per entry (bias_instability is the first of them,
  // kept in its place for the readers of one-state files, not an extra state).
  j["gauss_markov_states"] = nlohmann::json::array();
  j["gauss_markov_states_note"] =
      "one first-order Gauss-Markov state per entry, ordered by correlation time: every term the "
      "fit identified, else the one matched to the bias-instability floor; bias_instability "
      "repeats the first entry (it is not a further state)";

  {
    nlohmann::json w;
    const auto& n = c.random_walk;
    w["N"] = coefficient_json(n, n_unit);
    const bool ok = n.identified && n.value > 0.0;
    const double nan = std::nan("");
    w["psd"] = quantity_json(ok ? n.value * n.value : nan, psd_white);
    w["discrete_sigma"] = quantity_json(ok ? n.value / std::sqrt(dt) : nan, x);
    w["discrete_sigma"]["formula"] = "N / sqrt(dt)";
    if (!ok) w["note"] = "white noise not identified: no process noise derived";
    j["white_noise"] = std::move(w);
  }
  {
    nlohmann::json b;
    const auto& bi = c.bias_instability;
    b["B"] = coefficient_json(bi, x);
    b["model"] = "first_order_gauss_markov";
    b["equation"] = "db/dt = -b / T_c + w, E[w w'] = q_c delta, q_c = 2 sigma^2 / T_c";
    double sigma = std::nan("");
    double tc = std::nan("");
    std::string method;
    std::string note;
    std::vector<GaussMarkovTerm> fitted;
    for (const auto& g : c.gauss_markov) {
      if (identified(g)) fitted.push_back(g);
    }
    if (!fitted.empty()) {
      sigma = fitted.front().sigma.value;
      tc = fitted.front().correlation_time_s.value;
      method = fitted.size() == 1
                   ? "fitted: the Gauss-Markov term identified by the fit, used as is"
                   : fmt::format("fitted: the first (shortest correlation time) of the {} Gauss-Markov "
                                 "terms identified by the fit; every one is a state of "
                                 "gauss_markov_states",
                                 fitted.size());
      // One state per fitted term, by correlation time.
      for (const auto& g : fitted) {
        nlohmann::json s;
        s["source"] = "fitted";
        add_gauss_markov_state(s, g.sigma.value, g.correlation_time_s.value, dt, x, psd_walk);
        j["gauss_markov_states"].push_back(std::move(s));
      }
    } else if (bi.identified && bi.value > 0.0) {
      const double floor = std::sqrt(2.0 * std::numbers::ln2 / std::numbers::pi) * bi.value;
      sigma = floor / kGaussMarkovPeakRatio;
      double tau_floor = std::nan("");
      if (bias_floor_tau_s) {
        tau_floor = *bias_floor_tau_s;
        note = "tau of the Allan floor given by the caller: " + round_trip_number(tau_floor) + " s";
      } else if (c.random_walk.identified && c.rate_random_walk.identified &&
                 c.random_walk.value > 0.0 && c.rate_random_walk.value > 0.0) {
        tau_floor = std::sqrt(3.0) * c.random_walk.value / c.rate_random_walk.value;
        note =
            "tau of the Allan floor = tau_opt = sqrt(3) N / K = " + round_trip_number(tau_floor) +
            " s (paper eq. 1, bottom of the N + K model)";
      } else {
        note =
            "correlation time unknown: needs K (for tau_opt = sqrt(3) N/K) or the tau of "
            "the Allan floor; sigma only";
      }
      tc = tau_floor / kGaussMarkovPeakTau;
      method =
          "matched: the Gauss-Markov process whose Allan-deviation peak (0.6174 sigma at "
          "tau = 1.8926 T_c) equals the bias-instability floor sqrt(2 ln2/pi) B at tau_floor: "
          "sigma = sqrt(2 ln2/pi) B / 0.6174 = 1.0760 B, T_c = tau_floor / 1.8926 "
          "(IEEE Std 952-1997 Annex C; an approximation: flicker noise is not Markov)";
    } else {
      note = "bias instability not identified: no Gauss-Markov state derived";
    }
    b["method"] = method.empty() ? nlohmann::json(nullptr) : nlohmann::json(method);
    add_gauss_markov_state(b, sigma, tc, dt, x, psd_walk);
    if (fitted.empty() && std::isfinite(sigma) && std::isfinite(tc) && tc > 0.0) {
      nlohmann::json s;
      s["source"] = "matched to the bias-instability floor";
      add_gauss_markov_state(s, sigma, tc, dt, x, psd_walk);
      j["gauss_markov_states"].push_back(std::move(s));
    }
    if (!note.empty()) b["note"] = note;
    j["bias_instability"] = std::move(b);
  }
  {
    nlohmann::json k;
    const auto& rrw = c.rate_random_walk;
    k["K"] = coefficient_json(rrw, k_unit);
    const bool ok = rrw.identified && rrw.value > 0.0;
    const double nan = std::nan("");
    k["psd"] = quantity_json(ok ? rrw.value * rrw.value : nan, psd_walk);
    k["discrete_sigma"] = quantity_json(ok ? rrw.value * std::sqrt(dt) : nan, x);
    k["discrete_sigma"]["formula"] = "K sqrt(dt) (random-walk step per sample)";
    if (!ok) k["note"] = "rate random walk not identified: no bias random-walk state derived";
    j["rate_random_walk"] = std::move(k);
  }
  return j;
}

}  // namespace imunoise
