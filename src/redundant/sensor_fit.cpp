#include "imunoise/redundant/sensor_fit.hpp"

#include <algorithm>

#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"

namespace imunoise::redundant {

SensorModel fit_sensor_model(std::span<const double> rate_rad_s, double rate_hz, const std::string& source) {
  const double tau0_s = 1.0 / rate_hz;
  const auto phase = phase_from_rate(rate_rad_s, tau0_s, compensated_mean(rate_rad_s.first(std::min<std::size_t>(rate_rad_s.size(), 1u << 20))));
  const auto factors = estimator_averaging_factors(Estimator::oadev, parse_tau_grid("octave"), rate_hz, phase.size());
  const auto points = oadev(phase, tau0_s, factors);
  fit::FitOptions options;
  const fit::FitResult result = fit::fit_allan(points, phase.size(), tau0_s, options);
  if (result.summary.termination == fit::Termination::degenerate_input ||
      result.summary.termination == fit::Termination::too_few_points) {
    throw InputError(source + ": cannot fit the sensor's noise model: " + result.summary.message +
                     "; give its fit with --from");
  }
  SensorModel model;
  model.source = source;
  model.coefficients = result.coefficients;
  model.coefficients.quantity = Quantity::angular_rate;
  return model;
}

}  // namespace imunoise::redundant
