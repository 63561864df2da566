#pragma once
// What every filter export is written from: the measured noise model of a gyro triad and of an
// accelerometer triad (either may be absent), the sample rate, the inflation factor and a
// line saying what was measured. Filters take one value per term for a triad; a model made
// from several axes keeps, per term, the largest axis (the conservative choice) and says so.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/load/record.hpp"
#include "imunoise/noise_coefficients.hpp"

namespace imunoise::exports {

/// One axis as fitted: its channel name and coefficients (SI, quantity angular_rate or
/// acceleration).
struct AxisFit {
  std::string channel;
  NoiseCoefficients coefficients;
};

/// The model of one sensor triad (or a single axis).
struct SensorModel {
  NoiseCoefficients coefficients;  ///< per term, the axis with the largest value (SI)
  std::string channels;            ///< "gyro_x gyro_y gyro_z", for the files' comments
  std::string selection;           ///< how the value was chosen, e.g. "largest of 3 axes"
  /// The axes it was made from, as fitted: what the formats cannot carry (Gauss-Markov,
  /// sinusoid) is said from these (not_carried).
  std::vector<AxisFit> axes;
};

struct ExportModel {
  std::optional<SensorModel> gyro;   ///< absent: no gyro channel was measured
  std::optional<SensorModel> accel;  ///< absent: no accelerometer channel was measured
  double rate_hz = 0.0;              ///< IMU sample rate (Hz), > 0
  double inflation = 1.0;            ///< factor on every noise value (std-like; variances x F^2)
  std::string source;                ///< the recording, e.g. "imu.bag" (comments only)
  std::string topic = "/imu0";       ///< rostopic for Kalibr / OpenVINS
  /// PX4 EKF2 prediction rate (Hz): 1e6 / EKF2_PREDICT_US, PX4's default 10000 us -> 100 Hz.
  double px4_ekf_rate_hz = 100.0;
};

/// The fit of one record as an axis: its channel (container channel, else the record's name)
/// and coefficients; a record without a unit has quantity dimensionless (make_export_model
/// then refuses it: a filter file needs SI values).
AxisFit axis_fit(const Record& record, const NoiseCoefficients& coefficients);

/// The triad model from per-axis fits, all of one quantity: per term the identified axis with
/// the largest value, its interval with it; a term identified on no axis stays unidentified
/// (with the first axis's note). Throws InputError for no axes or mixed quantities.
SensorModel combine_axes(std::span<const AxisFit> axes);

/// An ExportModel from fits of any channels: gyro channels (angular_rate) form the gyro triad,
/// accelerometer channels (acceleration) the accelerometer one; other quantities are ignored.
/// Throws InputError when there is neither (naming the unit fix), or for a non-positive rate
/// or inflation.
ExportModel make_export_model(std::span<const AxisFit> fits, double rate_hz, double inflation,
                              std::string source);

/// One sentence per axis and kind of term that the filter formats have no field for (every
/// identified Gauss-Markov term, the sinusoid), "gyro_x: 2 Gauss-Markov terms (...) not
/// carried: <format> has no ...": written as comments in each file and as warnings by the
/// command line. Empty when the model has none.
std::vector<std::string> not_carried(const ExportModel& model, std::string_view format);

/// Throws InputError naming `target` for a non-positive rate or inflation, or when neither
/// sensor is present.
void check_export_model(const ExportModel& model, const std::string& target);

}  // namespace imunoise::exports
