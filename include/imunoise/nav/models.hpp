#pragma once
// The four models one by one (navigation_error() runs those asked). Each takes the options,
// the noise terms of the x (north), y (east), z (down) gyros and accelerometers in SI and the
// reported times, and
// returns the model's series with its assumptions stated (navigation.hpp).
#include <array>
#include <vector>

#include "imunoise/nav/navigation.hpp"

namespace imunoise::nav {

using AxisTerms = std::array<GyroTerms, 3>;
using AccelAxisTerms = std::array<AccelTerms, 3>;

/// The terms of the whole IMU, x (north), y (east), z (down).
struct ImuTerms {
  AxisTerms gyro;
  AccelAxisTerms accel;
};

/// Eq. 6 as published (paper.hpp) with sigma_eps = options.paper_sigma_eps_rad_s, or the
/// paper's reading (east gyro's N value as a rate). north = path, east = R * longitude,
/// radial = sqrt(2) path (the paper gives none).
ModelSeries paper_series(const NavOptions& options, const ImuTerms& terms, const std::vector<double>& t_s);

/// Closed forms per term (schuler.hpp), north channel from the y gyro and the x accelerometer,
/// east from the x gyro and the y accelerometer.
ModelSeries schuler_series(const NavOptions& options, const ImuTerms& terms, const std::vector<double>& t_s);

/// Exact discrete propagation P <- Phi P Phi' + Qd of the augmented error model at dt_s.
/// Accuracy: equals the closed forms to ~1e-10 relative where they apply (single channel,
/// Earth rate off; tests/nav).
ModelSeries covariance_series(const NavOptions& options, const ImuTerms& terms, const std::vector<double>& t_s);

/// options.runs runs of the error model driven by simulated gyro samples at 1/dt_s Hz
/// (sim::ChannelGenerator; run r uses seed SplitMix64(seed + r * golden).next(), channel = axis).
/// Runs are processed in fixed blocks on options.threads threads and merged in block order, so
/// the result does not depend on the thread count.
ModelSeries montecarlo_series(const NavOptions& options, const ImuTerms& terms, const std::vector<double>& t_s);

}  // namespace imunoise::nav
