#include "imunoise/export/audit.hpp"

#include <cmath>
#include <functional>
#include <numbers>

#include <fmt/core.h>

namespace imunoise::exports {

std::string_view verdict_name(Verdict v) {
  switch (v) {
    case Verdict::consistent: return "consistent";
    case Verdict::inflated: return "inflated";
    case Verdict::too_small: return "too_small";
    case Verdict::mistake: return "mistake";
    case Verdict::not_checked: return "not_checked";
  }
  return "?";
}

namespace {

struct Slip {
  std::function<double(double)> apply;  // expected value -> what the slip writes
  std::string label;
};

bool is_variance(Form f) { return f == Form::psd || f == Form::variance_imu; }

std::vector<Slip> slips(Form form, double f, double fe) {
  const double deg = 180.0 / std::numbers::pi;
  const bool var = is_variance(form);
  const double d = var ? deg * deg : deg;
  std::vector<Slip> out;
  const auto times = [](double k) { return [k](double v) { return v * k; }; };
  switch (form) {
    case Form::density:
      out.push_back({times(std::sqrt(f)), "x sqrt(rate): a discrete per-sample value (N sqrt(f)) where the "
                                          "continuous density belongs"});
      out.push_back({times(1.0 / std::sqrt(f)), "/ sqrt(rate): the density divided by sqrt(f)"});
      break;
    case Form::discrete_imu:
      out.push_back({times(1.0 / std::sqrt(f)), "/ sqrt(rate): the continuous density (Kalibr's value) where the "
                                                "per-sample value c sqrt(f) belongs"});
      out.push_back({times(std::sqrt(f)), "x sqrt(rate): sqrt(f) applied twice"});
      break;
    case Form::discrete_ekf:
      out.push_back({times(1.0 / std::sqrt(fe)), "/ sqrt(EKF rate): the continuous density where the value at the "
                                                 "EKF rate c sqrt(f_ekf) belongs"});
      if (std::abs(f - fe) > 1e-9 * f) {
        out.push_back({times(std::sqrt(f / fe)), "sqrt(IMU rate / EKF rate): discretised at the IMU rate instead of "
                                                 "the EKF prediction rate"});
      }
      break;
    case Form::psd:
      out.push_back({times(f), "x rate: the variance of one sample (N^2 f) where the continuous PSD belongs"});
      out.push_back({times(1.0 / f), "/ rate: the PSD divided by f"});
      break;
    case Form::variance_imu:
      out.push_back({times(1.0 / f), "/ rate: the continuous PSD (N^2) where the per-sample variance N^2 f belongs"});
      out.push_back({times(f), "x rate: f applied twice"});
      break;
  }
  out.push_back({times(d), "deg for rad: the value in degrees where radians belong"});
  out.push_back({times(1.0 / d), "rad for deg: the value divided by 180/pi"});
  if (var) {
    out.push_back({[](double v) { return std::sqrt(v); }, "sigma for sigma^2: a standard deviation where a "
                                                          "variance belongs"});
  } else {
    out.push_back({[](double v) { return v * v; }, "sigma^2 for sigma: a variance where a standard deviation "
                                                   "belongs"});
  }
  return out;
}

AuditItem check(const ParamValue& p, const ExportModel& m) {
  AuditItem item;
  item.param = p;
  const auto& sensor = p.spec.sensor == Sensor::gyro ? m.gyro : m.accel;
  const char* sensor_name = p.spec.sensor == Sensor::gyro ? "gyroscope" : "accelerometer";
  const char* symbol = p.spec.term == Term::white ? "N" : "K";
  if (!sensor) {
    item.message = fmt::format("not checked: the recording has no {} channel", sensor_name);
    return item;
  }
  const Coefficient& c =
      p.spec.term == Term::white ? sensor->coefficients.random_walk : sensor->coefficients.rate_random_walk;
  if (!(c.identified && c.value > 0.0)) {
    item.message = fmt::format("not checked: the recording does not identify the {} {}{}", sensor_name, symbol,
                               c.note.empty() ? "" : " (" + c.note + ")");
    return item;
  }
  const double f = m.rate_hz;
  const double fe = m.px4_ekf_rate_hz;
  const auto value_of = [&](double coefficient) { return file_value(p.spec.form, coefficient, f, fe); };
  item.expected = value_of(c.value);
  item.low = std::isfinite(c.ci_low) && c.ci_low > 0.0 ? value_of(c.ci_low) : item.expected;
  item.high = std::isfinite(c.ci_high) ? value_of(c.ci_high) : item.expected;
  item.ratio = p.value / item.expected;
  const double v = p.value;
  const int level = static_cast<int>(std::lround(sensor->coefficients.confidence_level * 100.0));
  const std::string measured = fmt::format("measured {} = {:.4g} {} ({}% interval {:.4g} .. {:.4g})",
                                           form_formula(p.spec.form, p.spec.term), item.expected, p.spec.unit,
                                           level, item.low, item.high);
  if (v >= item.low && v <= item.high) {
    item.verdict = Verdict::consistent;
    item.message = "consistent: " + measured;
    return item;
  }
  // Every slip that explains the value within the interval (two can: deg^2 and sigma for
  // sigma^2 may coincide for one number); all are named.
  for (const auto& s : slips(p.spec.form, f, fe)) {
    const double lo = s.apply(item.low);
    const double hi = s.apply(item.high);
    if (v >= std::min(lo, hi) && v <= std::max(lo, hi)) {
      if (!item.mistake.empty()) item.mistake += ", or ";
      item.mistake += s.label;
    }
  }
  if (!item.mistake.empty()) {
    item.verdict = Verdict::mistake;
    item.message = fmt::format("WRONG by {}; {}", item.mistake, measured);
    return item;
  }
  if (v > item.high) {
    item.verdict = Verdict::inflated;
    item.message = fmt::format("inflated x{:.3g} (a common, deliberate margin for unmodelled effects; if not "
                               "meant, check the units); {}",
                               item.ratio, measured);
  } else {
    item.verdict = Verdict::too_small;
    item.message = fmt::format("TOO SMALL x{:.3g}: the filter will be over-confident; {}", 1.0 / item.ratio,
                               measured);
  }
  return item;
}

}  // namespace

AuditResult audit(const ParamsFile& file, const ExportModel& measured) {
  check_export_model(measured, "check");
  AuditResult r;
  r.path = file.path;
  r.target = file.target;
  r.rate_hz = measured.rate_hz;
  for (const auto& p : file.values) {
    r.items.push_back(check(p, measured));
    if (r.items.back().verdict == Verdict::mistake || r.items.back().verdict == Verdict::too_small) r.ok = false;
  }
  if (file.rate_hz && std::abs(*file.rate_hz - measured.rate_hz) > 1e-9 * measured.rate_hz) {
    r.notes.push_back(fmt::format("the file states a rate of {:g} Hz; the recording is sampled at {:g} Hz", *file.rate_hz,
                                  measured.rate_hz));
  }
  for (const auto& k : file.missing) r.notes.push_back(k + " is not in the file (not checked)");
  if (file.target == Target::px4) {
    r.notes.push_back(fmt::format("PX4 values are checked at an EKF rate of {:g} Hz (EKF2_PREDICT_US {:g} us)",
                                  measured.px4_ekf_rate_hz, 1e6 / measured.px4_ekf_rate_hz));
  }
  return r;
}

nlohmann::json audit_json(const AuditResult& r) {
  nlohmann::json values = nlohmann::json::array();
  for (const auto& i : r.items) {
    nlohmann::json v{{"key", i.param.spec.key},
                     {"sensor", i.param.spec.sensor == Sensor::gyro ? "gyroscope" : "accelerometer"},
                     {"term", i.param.spec.term == Term::white ? "N" : "K"},
                     {"unit", i.param.spec.unit},
                     {"value", i.param.value},
                     {"verdict", verdict_name(i.verdict)},
                     {"message", i.message}};
    if (i.verdict != Verdict::not_checked) {
      v["expected"] = i.expected;
      v["interval"] = {i.low, i.high};
      v["ratio"] = i.ratio;
      v["formula"] = form_formula(i.param.spec.form, i.param.spec.term);
    }
    v["mistake"] = i.mistake.empty() ? nlohmann::json(nullptr) : nlohmann::json(i.mistake);
    values.push_back(std::move(v));
  }
  return {{"file", r.path},  {"target", target_name(r.target)}, {"rate_hz", r.rate_hz},
          {"ok", r.ok},      {"notes", r.notes},                {"values", values}};
}

std::string audit_table(const AuditResult& r) {
  std::string out = fmt::format("{} ({} parameters) against the recording at {:g} Hz\n", r.path, target_name(r.target),
                                r.rate_hz);
  for (const auto& i : r.items) {
    out += fmt::format("  {:<32} {:<14.6g} {:<18} {}\n", i.param.spec.key, i.param.value, i.param.spec.unit, i.message);
  }
  for (const auto& n : r.notes) out += "  note: " + n + "\n";
  out += r.ok ? "result: no mistake found\n" : "result: MISTAKES found (see WRONG / TOO SMALL above)\n";
  return out;
}

}  // namespace imunoise::exports
