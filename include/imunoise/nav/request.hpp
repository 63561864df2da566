#pragma once
// What a user asks `imunoise nav` or Python's `imunoise.nav` for, in the user's units, turned
// into NavOptions (SI). The checks and conversions are here once; each edge only maps its
// flags or keywords and says how it names them in messages.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/report.hpp"

namespace imunoise::nav {

struct NavRequest {
  AxisCoefficients coefficients;  ///< every axis's coefficients, in `units` (0: absent)
  bool coefficients_given = false;
  /// Fits per axis (x north, y east, z down): all empty, all three, or the same fit on each.
  std::array<std::optional<GyroAxisNoise>, 3> fitted_axes;
  /// Every accelerometer axis's coefficients, in `accel_units` (0: absent; N is the velocity
  /// random walk, K the acceleration random walk, Q the velocity quantization).
  AxisCoefficients accel_coefficients;
  /// Accelerometer fits per axis (from analyze's report.json); not beside accel_coefficients.
  std::array<std::optional<AccelAxisNoise>, 3> fitted_accel_axes;
  double accel_bias = 0.0;            ///< constant accelerometer bias on every axis (`accel_units`)
  std::string accel_units = "m/s^2";  ///< m/s^2, g, mg, ug
  double bias = 0.0;              ///< constant drift on every axis (`units`), with either
  std::string units = "deg/s";    ///< unit of the coefficients, the bias and sigma_eps
  double hours = 1.0;             ///< operating time (h)
  std::vector<double> outage_s;   ///< GNSS outage horizons (s)
  double measured_s = 0.0;        ///< the record length behind the fits (s; 0: unknown)
  double align_s = 0.0;           ///< stationary alignment before navigation (s; 0: none)
  double initial_pos_m = 0.0;     ///< 1-sigma errors at the outage start, per axis
  double initial_vel_m_s = 0.0;
  double initial_att_deg = 0.0;
  double latitude_deg = 58.5;
  double velocity_m_s = 0.0;
  double step_s = 60.0;           ///< reporting interval (s); clipped to the operating time
  double dt_s = 1.0;
  std::string models = "schuler,covariance";
  std::size_t runs = 1000;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  std::optional<double> sigma_eps;  ///< paper model (`units`)
  bool earth_rate = true;
  bool signed_constants = false;
  CoefficientNames names{"--", '-'};  ///< how the edge names its options in messages
  /// How the edge names its fits: one for every axis, and one per axis.
  std::string fit_option = "--from";
  std::string per_axis_fit_option = "--from-x, --from-y and --from-z";
};

/// NavOptions of a request. InputError naming the option (as `names` spells it) and the fix for
/// a unit that is not an angular rate, a non-finite bias, both coefficients and fits, some but
/// not all per-axis fits, a non-positive operating time or a latitude beyond +-90 deg.
NavOptions plan_navigation(const NavRequest& request);

}  // namespace imunoise::nav
