#pragma once
// The in-motion analysis of a redundant unit's recordings (one per sensor, in the geometry's
// order): the checks that make them one unit (same rate, same length), each sensor's in-motion
// curve (redundant/in_motion.hpp) and its noise-model fit (fit_curve), or why the geometry
// cannot give it one; the `in_motion` document of `imunoise redundant --in-motion` and Python.
//
// The fit: the in-motion estimate of a sensor's Allan variance has a larger variance than a
// direct oadev of the same length (it also carries the other sensors' noise). The fit's weights
// and intervals model a direct oadev over n_phase samples, so each sensor's curve is fitted as
// a record of n_eff = n_phase * min_tau(edf_in_motion / edf_direct) phase samples (at least
// 2 m_max + 2, so no tau is dropped), which gives it the in-motion precision (conservative at
// the taus where the ratio is larger); taus whose in-motion EDF is below kMinFitEdf are left
// out of the fit. Warnings say both.
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/deviation.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/load/record.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/redundant/in_motion.hpp"

namespace imunoise::study {

/// In-motion over static value of one noise term, with an interval at the fit's level.
struct Inflation {
  bool available = false;
  double ratio = 0.0;
  double ci_low = 0.0;
  double ci_high = 0.0;
  std::string reason;  ///< why not available (a term not identified in one of the fits)
};

struct InMotionSensor {
  Record record;                        ///< the recording's description (its samples released)
  std::optional<Record> static_record;  ///< the same sensor at rest (description only), if given
  std::optional<fit::FitResult> static_fit;
  /// N, B, K (fit::kN, kB, kK): in-motion / static, when a static recording is given.
  std::vector<std::pair<int, Inflation>> inflation;
  bool identified = false;              ///< the geometry gives this sensor its own curve
  std::string reason;                   ///< why not (identifiability), or why the fit failed
  std::optional<fit::FitResult> fit;    ///< the in-motion noise model (SI)
  std::size_t n_phase_effective = 0;    ///< record length the fit was given (header comment)
};

struct InMotionUnit {
  redundant::Geometry geometry;
  redundant::InMotionResult result;
  std::vector<InMotionSensor> sensors;  ///< in the order given
  std::vector<std::string> notes;
};

/// Taus of an in-motion curve with EDF below this are left out of its fit (their estimate
/// can be off by a factor of several; they still appear in the curve).
inline constexpr double kMinFitEdf = 2.0;

/// Standard gravity (m/s^2), for g-sensitivity in deg/h/g.
inline constexpr double kStandardGravity_m_s2 = 9.80665;

/// The factor from SI (rad/s per m/s^2) to the reported g-sensitivity unit and its name:
/// deg/h/g for a gyro record, else the record's unit per m/s^2.
std::pair<double, std::string> g_sensitivity_unit(const Record& record);

/// The points of a curve the fit uses: finite EDF >= kMinFitEdf and a non-zero estimate.
std::vector<DevPoint> fittable_points(std::span<const DevPoint> curve);

/// n_eff of the header comment for one sensor's in-motion curve over n_phase phase samples:
/// n_phase times the smallest ratio of the in-motion EDF to a direct oadev's over the points.
std::size_t effective_phase_count(std::span<const DevPoint> curve, std::size_t n_phase);

/// `recordings` must keep their rates (LoadOptions::keep_rates) and be in the geometry's order.
/// InputError naming the files when their number differs from the geometry's axes, their rates
/// or lengths differ, or the geometry has no parity space (no more sensors than axes); with
/// options.require_per_sensor also when the geometry cannot identify every sensor.
/// With `specific_force_m_s2` (x, y, z of the body, SI, the recordings' length: the unit's fused
/// accelerometers, e.g. mean_specific_force or read_container_unit) the gyros' g-sensitivity is
/// estimated and removed with the rest of the leakage.
InMotionUnit analyze_in_motion(const redundant::Geometry& geometry, std::vector<Record> recordings,
                               const redundant::InMotionOptions& options, const fit::FitOptions& fit_options,
                               const std::array<std::vector<double>, 3>& specific_force_m_s2 = {});

/// The ratio a / b of two fitted coefficients with its interval: each coefficient's interval is
/// taken as log-normal (sd of ln = ln(high / low) / (2 z), z the two-sided normal quantile at
/// `level`), the two independent (different recordings), so ln(a / b) has the summed variance.
/// Not available when either is not identified or its lower bound is not positive.
Inflation coefficient_ratio(const Coefficient& in_motion, const Coefficient& at_rest, double level);

/// Fits each sensor's static recording (the one Record fit, study::fit_channel) and sets its
/// in-motion/static ratio per term. InputError when their number differs from the sensors'.
void compare_with_static(InMotionUnit& unit, std::vector<Record> static_recordings,
                         const fit::FitOptions& fit_options);

/// The `in_motion` document: geometry, rate_hz, samples, unit, identifiability {sensors,
/// parity_channels, equations, rank, per_sensor, reason, unobservable}, common {description,
/// weights, points[{tau_s, adev, edf, ci_low, ci_high}]}, leakage {removed, coefficients (B),
/// motion_rms, convention, timing, g_sensitivity}, sensors[{source, identified, leakage
/// {scale_factor_ppm, misalignment_mrad, time_offset_ms (timing), g_sensitivity {value, se,
/// unit} (deg/h/g for gyros; with a specific force)}, static_fit, inflation {N, B, K: {ratio, ci_low, ci_high} | {reason}}
/// (with static recordings), reason |
/// curve {unit, ci_level, points[{m, tau_s, adev, n, edf, ci_low, ci_high}]}, fit (the
/// `imunoise fit` document) | fit_error}], notes. Deviations in the recordings' unit.
nlohmann::json in_motion_json(const InMotionUnit& unit, const fit::FitOptions& fit_options);

/// `--format table`: identifiability, per sensor its fitted N, B, K (with intervals) and its
/// curve, or why it has none; then the weighted mean level.
std::string in_motion_table(const InMotionUnit& unit);

}  // namespace imunoise::study
