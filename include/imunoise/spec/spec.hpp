#pragma once
// A sensor datasheet ("spec"): the noise-model limits a measured sensor is compared against
// (see comparison.hpp), plus the descriptive ratings of the datasheet (range, bandwidth, scale
// factor) kept for the report.
//
// Every value is kept twice: as written in the datasheet (value + unit text) and in SI, in the
// units of NoiseCoefficients (noise_coefficients.hpp): for a gyroscope N in rad/sqrt(s),
// B in rad/s, K in rad/s/sqrt(s); for an accelerometer replace rad by m/s.
//
// Noise density and PSD convention. The IEEE 952 angle random walk N is the square root of the
// two-sided power spectral density of the white rate noise (sigma^2(tau) = N^2/tau, paper
// eq. 4): a density given per sqrt(Hz) under the two-sided convention equals N; a one-sided
// density is sqrt(2) larger, so N = density/sqrt(2). A datasheet noise density in .../sqrt(Hz)
// must say which convention it uses (`psd: one_sided | two_sided`); an ARW given in
// deg/sqrt(h) (or any .../sqrt(h), .../sqrt(s)) is N itself and takes no convention.
//
// File format: YAML, documented in docs/spec.md, example examples/specs/tg100.yaml.
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/units.hpp"

namespace imunoise {

/// What a spec describes: a gyroscope (angular rate) or an accelerometer (acceleration).
enum class SensorKind { gyroscope, accelerometer };

/// How a noise density per sqrt(Hz) relates to the power spectral density.
enum class PsdConvention {
  not_applicable,  ///< the value is an Allan coefficient (.../sqrt(h), .../sqrt(s)), not a density
  one_sided,       ///< density = sqrt(one-sided PSD) = sqrt(2) * N
  two_sided,       ///< density = sqrt(two-sided PSD) = N (IEEE 952, Kalibr)
};

/// "gyroscope" / "accelerometer".
std::string_view sensor_kind_name(SensorKind kind);
/// "not_applicable" / "one_sided" / "two_sided".
std::string_view psd_convention_name(PsdConvention convention);
/// The quantity of a sensor's output: angular_rate for a gyroscope, acceleration otherwise.
Quantity sensor_quantity(SensorKind kind);

/// One noise-model limit of a datasheet (N, B or K).
struct SpecTerm {
  double value = std::numeric_limits<double>::quiet_NaN();  ///< as written, in `unit`
  std::string unit;    ///< as written, e.g. "deg/sqrt(h)", "mg/sqrt(Hz)", "deg/h"
  double to_si = 1.0;  ///< value_si = value * to_si (includes the PSD convention)
  double value_si = std::numeric_limits<double>::quiet_NaN();  ///< in NoiseCoefficients units
  PsdConvention psd = PsdConvention::not_applicable;
  /// Relative tolerance of the pass rule: pass if measured <= value_si * (1 + tolerance).
  double tolerance = 0.0;
};

/// A descriptive rating of the datasheet (range, bandwidth, scale factor).
struct SpecRating {
  double value = std::numeric_limits<double>::quiet_NaN();  ///< as written
  std::string unit;                                         ///< as written
  /// SI: range in rad/s or m/s^2 (half-width of the symmetric range), bandwidth in Hz,
  /// scale factor in V/(rad/s) or V/(m/s^2).
  double value_si = std::numeric_limits<double>::quiet_NaN();
};

struct Spec {
  std::string name;         ///< short name, e.g. "tg100"
  std::string description;  ///< free text (model, maker, datasheet table)
  std::string source;       ///< "builtin:tg100" or the file path it was loaded from
  SensorKind sensor = SensorKind::gyroscope;
  double tolerance = 0.0;                    ///< default relative tolerance of every term (>= 0)
  std::optional<SpecTerm> random_walk;       ///< N: ARW / VRW / white-noise density
  std::optional<SpecTerm> bias_instability;  ///< B: flicker floor coefficient
  std::optional<SpecTerm> rate_random_walk;  ///< K
  std::optional<SpecRating> range;           ///< +/- full scale
  std::optional<SpecRating> bandwidth;       ///< -3 dB bandwidth
  std::optional<SpecRating> scale_factor;    ///< analog output sensitivity
};

/// Reads a YAML spec file (format: docs/spec.md). Throws InputError naming the file, the line
/// and the key, and saying how to fix it, for: a missing file, malformed YAML, an unknown or
/// missing key, a unit that is unknown or of the wrong quantity, a negative or non-finite
/// value, an unknown or missing PSD convention.
Spec load_spec_file(const std::string& path);

/// Parses the YAML text of a spec; `source` names it in messages (e.g. the file path).
Spec parse_spec_yaml(std::string_view yaml_text, const std::string& source);

/// A spec compiled into the library. Known names: builtin_spec_names(). Throws InputError for
/// an unknown name, listing the known ones.
///   "tg100": TG-100 MEMS gyro, paper Table 1: ARW 0.05 deg/sqrt(h), bias instability 2 deg/h,
///            range +/-100 deg/s, bandwidth 50 Hz, scale factor 20 mV/(deg/s); tolerance 0.
///   "adis16405": ADIS16405 MEMS IMU gyros, datasheet: ARW 2.0 deg/sqrt(h), in-run bias
///            stability 0.007 deg/s, range +/-300 deg/s, bandwidth 330 Hz (digital output,
///            no scale factor); tolerance 0.
Spec builtin_spec(std::string_view name);

/// Names of the built-in specs, sorted.
std::vector<std::string> builtin_spec_names();

/// A built-in spec name or the path of a spec file. Throws InputError when it is neither,
/// listing the built-in names.
Spec resolve_spec(const std::string& name_or_path);

/// SI conversion factor of a noise-model unit for term N, B or K of a sensor, as accepted in
/// spec files (docs/spec.md lists them): value_si = value * factor. For a noise density in
/// .../sqrt(Hz) the factor includes the PSD convention (one_sided divides by sqrt(2)); pass
/// not_applicable for other units. Throws InputError (message without file context: the
/// caller adds it) for an unknown unit, a unit of the wrong kind, or a convention that is
/// missing for a density or given for a non-density.
/// @param symbol 'N', 'B' or 'K'
double spec_term_to_si(char symbol, SensorKind sensor, std::string_view unit,
                       PsdConvention convention);

/// True when `unit` is a noise density per sqrt(Hz) (the PSD convention applies).
bool is_noise_density_unit(std::string_view unit);

}  // namespace imunoise
