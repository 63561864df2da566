#pragma once
// The navigation result as the user reads it: one JSON document shared by the command line
// (`imunoise nav --format json`), Python (`imunoise.nav`) and the study report; and the
// reading of a `fit` JSON document into a gyro axis's noise model (`--from FIT.json`).
//
// Document (interface.md, `nav`): times in s, angles in deg, distances in m, every series one
// value per reported time, no NaN (a value that does not exist is null):
//   {"latitude_deg", "duration_s", "step_s", "dt_s", "velocity_m_s", "earth_rate", "earth": {...},
//    "axes": [{"axis": "x", "direction": "north", "Q_deg", "N_deg_sqrt_s", ... customary ...}],
//    "absent_terms": [...], "notes": [...], "longitude_defined",
//    "models": [{"model", "assumptions", "t_s", "lat_deg", "lon_deg" (null at the pole),
//                "path_m" (= north_m), "north_m", "east_m", "radial_m",
//                paper: "sigma_eps_deg_s", "published", "sigma_eps_for_published_deg_s";
//                montecarlo: "runs", "seed", "path_se_m", "east_se_m", "radial_se_m",
//                            "path_mean_m", "path_mean_se_m", "east_mean_m", "east_mean_se_m";
//                covariance: "check": {"states", "max_asymmetry", "min_eigenvalue_ratio"}}]}
#include <array>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "imunoise/nav/navigation.hpp"
#include "imunoise/units.hpp"

namespace imunoise::nav {

/// The JSON document of a result.
nlohmann::json report_json(const NavResult& result);

/// Figure-ready CSV: one row per reported time, `t_s` then, per model, `<model>_lat_deg`,
/// `<model>_lon_deg` (empty at the pole), `<model>_path_m`, `<model>_east_m`, `<model>_radial_m`
/// and for montecarlo also `montecarlo_path_se_m`, `montecarlo_radial_se_m`. A header comment
/// line names the units.
std::string report_csv(const NavResult& result);

/// Plain-text table of the 1-hour values (or the final ones when the run is shorter or 1 h is
/// not a reported time) of every model side by side, with the paper's published figures when
/// the paper model was asked and the time is 1 h; notes and assumptions as # lines.
std::string report_table(const NavResult& result);

/// The noise of one gyro axis from the document `imunoise fit --format json` writes: the
/// terms Q N B K R (values in the document's unit, converted to SI; a term with
/// "identified": false is absent) and, when present and identified, GM. InputError naming
/// `source` and the missing or wrong field when the document is not a gyro fit.
GyroAxisNoise axis_from_fit_json(const nlohmann::json& document, const std::string& source);

/// Coefficients of one gyro axis as a user gives them, in `unit`: Q, N, B, K, R and a
/// Gauss-Markov sigma with its correlation time (s).
struct AxisCoefficients {
  double q = 0.0, n = 0.0, b = 0.0, k = 0.0, r = 0.0, gm_sigma = 0.0, gm_tau_s = 0.0;
};

/// How the edge names the coefficients in messages: "--N", "--gm-sigma" (command line) or "N",
/// "gm_sigma" (Python).
struct CoefficientNames {
  std::string prefix;
  char separator = '-';
};

/// The noise of one gyro axis from given coefficients, converted to SI. InputError naming the
/// coefficient when a noise intensity is negative or not finite, or a GM sigma has no
/// correlation time.
GyroAxisNoise axis_from_coefficients(const AxisCoefficients& c, const Unit& unit, const CoefficientNames& names);

/// Reads and parses the file, then axis_from_fit_json; InputError naming the file when it
/// cannot be read or is not JSON.
GyroAxisNoise axis_from_fit_file(const std::string& path);

/// The noise of the whole IMU from a document: a gyro fit (the same on every gyro axis, no
/// accelerometers) or analyze's report.json (each fitted channel with a unit on its axis by
/// imu_axes.hpp's rule: gyros by angular-rate units, accelerometers by acceleration units).
struct ImuFits {
  std::array<std::optional<GyroAxisNoise>, 3> gyro;
  std::array<std::optional<AccelAxisNoise>, 3> accel;
  std::array<std::string, 3> gyro_channels, accel_channels;  ///< the study's channel per axis
  double measured_s = 0.0;  ///< the shortest record the fits come from (n_samples / rate_hz; 0: unknown)
};
ImuFits imu_from_document(const nlohmann::json& document, const std::string& source);
ImuFits imu_from_file(const std::string& path);

}  // namespace imunoise::nav
