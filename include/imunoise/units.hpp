#pragma once
// Physical units: SI inside the library, customary units at its edges (input files, reports).
//
// A Unit is a name, what it measures and one factor: si_value = value * to_si. The SI units
// are rad/s, rad, m/s^2, m/s, 1 (dimensionless), s and V. Conversions are exact to the
// rounding of one multiplication (the factors are the correctly rounded double of the exact
// definition, e.g. 1 g = 9.80665 m/s^2 exactly, 1 deg = pi/180 rad).
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise {

/// What a unit measures. Rate-like quantities (angular_rate, acceleration, dimensionless
/// fractional frequency) integrate over time into angle-like ones (angle, velocity, time error).
enum class Quantity { angular_rate, angle, acceleration, velocity, dimensionless, time, voltage };

/// A unit of measure. Values convert as si_value = value * to_si.
struct Unit {
  std::string name;                     ///< canonical spelling, e.g. "deg/s" (also for aliases)
  Quantity quantity = Quantity::dimensionless;
  double to_si = 1.0;                   ///< SI value of 1 of this unit (SI unit of `quantity`)
};

/// Parses a unit name (case-sensitive, surrounding spaces ignored). Known names:
///   angular rate: rad/s, deg/s (dps, °/s), deg/h (deg/hr, dph, °/h), rad/h, mrad/s, mdeg/s,
///                 arcsec/s, deg/min, rpm
///   angle:        rad, deg (°), mrad, arcsec, arcmin
///   acceleration: m/s^2 (m/s2), g (= 9.80665 m/s^2), mg, ug (µg), ft/s^2 (ft/s2)
///   velocity:     m/s, ft/s
///   dimensionless (fractional frequency): 1 ("" and ff)
///   time:         s, ms, us (µs), ns
///   voltage:      V, mV
/// Throws InputError naming the text and listing the known units.
Unit parse_unit(std::string_view name);

/// Canonical names of every unit parse_unit knows, in the order listed above.
std::vector<std::string> known_unit_names();

/// "angular rate", "angle", ... for messages.
std::string_view quantity_name(Quantity quantity);

/// Name of the SI unit of a quantity: "rad/s", "rad", "m/s^2", "m/s", "1", "s", "V".
std::string_view si_unit_name(Quantity quantity);

/// The unit of the time integral of samples in `rate_unit`, time being in seconds:
/// deg/s -> deg, m/s^2 -> m/s, 1 -> s (fractional frequency -> time error). A rate without a
/// "/s" in its name keeps its name with "*s" appended (deg/h -> deg/h*s, g -> g*s); to_si is
/// unchanged because the seconds are SI. Throws InputError for a unit that is not a rate
/// (angle, velocity, time, voltage).
Unit integral_unit(const Unit& rate_unit);

/// Inverse of integral_unit: deg -> deg/s, rad -> rad/s, m/s -> m/s^2, s -> 1, deg/h*s -> deg/h.
/// Throws InputError for a unit that is not an angle, velocity or time.
Unit derivative_unit(const Unit& angle_unit);

/// value (in `unit`) -> SI.
[[nodiscard]] inline double to_si(double value, const Unit& unit) { return value * unit.to_si; }
/// SI value -> value in `unit`.
[[nodiscard]] inline double from_si(double value_si, const Unit& unit) { return value_si / unit.to_si; }

/// Named conversion factors. `X_to_Y` multiplies a value in X to give it in Y:
/// `rate_rad_s = rate_deg_h * units::deg_per_h_to_rad_per_s`; divide to go back.
namespace units {

inline constexpr double deg_to_rad = std::numbers::pi / 180.0;
inline constexpr double arcmin_to_rad = deg_to_rad / 60.0;
inline constexpr double arcsec_to_rad = deg_to_rad / 3600.0;
inline constexpr double min_to_s = 60.0;
inline constexpr double h_to_s = 3600.0;
/// Standard gravity (CGPM 1901, exact): 1 g = 9.80665 m/s^2.
inline constexpr double g_to_m_per_s2 = 9.80665;
/// International foot (exact): 1 ft = 0.3048 m.
inline constexpr double ft_to_m = 0.3048;
/// sqrt(1 h) = 60 sqrt(s), used by the random-walk units below.
inline constexpr double sqrt_h_to_sqrt_s = 60.0;

// Customary units of the IEEE 952 gyro noise-model coefficients (see interface.md):
/// Bias instability B: 1 deg/h = (pi/180) / 3600 rad/s.
inline constexpr double deg_per_h_to_rad_per_s = deg_to_rad / h_to_s;
/// Angle random walk N: 1 deg/sqrt(h) = (pi/180) / 60 rad/sqrt(s).
inline constexpr double deg_per_sqrt_h_to_rad_per_sqrt_s = deg_to_rad / sqrt_h_to_sqrt_s;
/// Rate random walk K: 1 deg/h/sqrt(h) = (pi/180) / (3600 * 60) rad/s/sqrt(s).
inline constexpr double deg_per_h_per_sqrt_h_to_rad_per_s_per_sqrt_s =
    deg_to_rad / (h_to_s * sqrt_h_to_sqrt_s);
/// Rate ramp R: 1 deg/h^2 = (pi/180) / 3600^2 rad/s^2.
inline constexpr double deg_per_h2_to_rad_per_s2 = deg_to_rad / (h_to_s * h_to_s);
// Quantization noise Q is customarily given in arcsec: use arcsec_to_rad.

}  // namespace units

/// A customary unit of a noise coefficient: its name, its SI name and the factor between them
/// (si_value = value * to_si).
struct CustomaryUnit {
  std::string_view name;
  std::string_view si_name;
  double to_si;
};

/// Customary units of the five gyro noise coefficients (interface.md, "Conventions").
inline constexpr CustomaryUnit customary_gyro_Q{"arcsec", "rad", units::arcsec_to_rad};
inline constexpr CustomaryUnit customary_gyro_N{"deg/sqrt(h)", "rad/sqrt(s)",
                                                units::deg_per_sqrt_h_to_rad_per_sqrt_s};
inline constexpr CustomaryUnit customary_gyro_B{"deg/h", "rad/s", units::deg_per_h_to_rad_per_s};
inline constexpr CustomaryUnit customary_gyro_K{
    "deg/h/sqrt(h)", "rad/s/sqrt(s)", units::deg_per_h_per_sqrt_h_to_rad_per_s_per_sqrt_s};
inline constexpr CustomaryUnit customary_gyro_R{"deg/h^2", "rad/s^2",
                                                units::deg_per_h2_to_rad_per_s2};

}  // namespace imunoise
