#include "imunoise/export/export_model.hpp"

#include <cmath>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/spec/exports.hpp"

namespace imunoise::exports {
namespace {

bool present(const Coefficient& c) { return c.identified && std::isfinite(c.value) && c.value > 0.0; }

// The largest identified value among the axes (a filter takes one number for the triad; the
// worst axis does not make it over-confident on any axis).
Coefficient largest(std::span<const AxisFit> axes, Coefficient NoiseCoefficients::*term) {
  const Coefficient* best = nullptr;
  for (const auto& a : axes) {
    const Coefficient& c = a.coefficients.*term;
    if (present(c) && (best == nullptr || c.value > best->value)) best = &c;
  }
  return best != nullptr ? *best : axes.front().coefficients.*term;
}

}  // namespace

AxisFit axis_fit(const Record& record, const NoiseCoefficients& coefficients) {
  AxisFit a{record.channel.empty() ? record.name : record.channel, coefficients};
  if (a.channel.empty()) a.channel = record.source;
  if (!record.unit_given) a.coefficients.quantity = Quantity::dimensionless;
  return a;
}

SensorModel combine_axes(std::span<const AxisFit> axes) {
  if (axes.empty()) throw InputError("export: no axis to build a sensor model from");
  SensorModel model;
  model.coefficients = axes.front().coefficients;
  for (const auto& a : axes) {
    if (a.coefficients.quantity != axes.front().coefficients.quantity) {
      throw InputError("export: channels " + axes.front().channel + " and " + a.channel +
                       " measure different quantities; fix: group gyro and accelerometer channels apart");
    }
    if (!model.channels.empty()) model.channels += ' ';
    model.channels += a.channel;
  }
  model.coefficients.quantization = largest(axes, &NoiseCoefficients::quantization);
  model.coefficients.random_walk = largest(axes, &NoiseCoefficients::random_walk);
  model.coefficients.bias_instability = largest(axes, &NoiseCoefficients::bias_instability);
  model.coefficients.rate_random_walk = largest(axes, &NoiseCoefficients::rate_random_walk);
  model.coefficients.rate_ramp = largest(axes, &NoiseCoefficients::rate_ramp);
  // No filter format has a Gauss-Markov or sinusoid field: not_carried says what is dropped.
  model.coefficients.gauss_markov.clear();
  model.coefficients.sinusoid.reset();
  model.axes.assign(axes.begin(), axes.end());
  model.selection = axes.size() == 1 ? "one axis"
                                     : fmt::format("per term the largest of {} axes", axes.size());
  return model;
}

std::vector<std::string> not_carried(const ExportModel& model, std::string_view format) {
  std::vector<std::string> out;
  for (const auto* sensor : {&model.gyro, &model.accel}) {
    if (!*sensor) continue;
    for (const auto& a : (*sensor)->axes) {
      for (const auto& line : imunoise::not_carried(a.coefficients, format)) out.push_back(a.channel + ": " + line);
    }
  }
  return out;
}

void check_export_model(const ExportModel& model, const std::string& target) {
  if (!(std::isfinite(model.rate_hz) && model.rate_hz > 0.0)) {
    throw InputError(fmt::format("{}: sample rate {:g} Hz is not positive; fix: pass --rate HZ", target,
                                 model.rate_hz));
  }
  if (!(std::isfinite(model.inflation) && model.inflation > 0.0)) {
    throw InputError(fmt::format("{}: inflation factor {:g} is not positive; fix: pass --inflate F with "
                                 "F > 0 (1 = measured values)",
                                 target, model.inflation));
  }
  if (!model.gyro && !model.accel) {
    throw InputError(target + ": neither a gyroscope nor an accelerometer channel was measured "
                              "(units of angular rate or acceleration); fix: give the channels' "
                              "units (--units)");
  }
}

ExportModel make_export_model(std::span<const AxisFit> fits, double rate_hz, double inflation,
                              std::string source) {
  std::vector<AxisFit> gyro;
  std::vector<AxisFit> accel;
  for (const auto& f : fits) {
    if (f.coefficients.quantity == Quantity::angular_rate) gyro.push_back(f);
    if (f.coefficients.quantity == Quantity::acceleration) accel.push_back(f);
  }
  ExportModel model;
  if (!gyro.empty()) model.gyro = combine_axes(gyro);
  if (!accel.empty()) model.accel = combine_axes(accel);
  model.rate_hz = rate_hz;
  model.inflation = inflation;
  model.source = std::move(source);
  check_export_model(model, "export");
  return model;
}

}  // namespace imunoise::exports
