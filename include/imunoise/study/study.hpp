#pragma once
// The whole study of a set of recorded channels, in one call:
//   curves (with confidence) -> noise-model fit -> datasheet comparison -> navigation error
//   -> (redundant geometry given) fused axes and fault detection
// and the one report document every output is rendered from (report.json as is; the HTML,
// Markdown, CSV, Kalibr file and figures from it: render.hpp, write.hpp).
//
// Entry point for every caller of a set of channels (analyze, demo, Python): run_study(); the
// fleet studies one record at a time with study_sensor() (study/sensor.hpp), the same stages.
// Channels must share one sample rate, and channels of one quantity one unit (a mixed set
// would put incomparable curves on one figure and cannot be fused); a channel whose stage
// fails is kept with its error when keep_going is set, otherwise the InputError propagates.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/fit/fit.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/detection.hpp"
#include "imunoise/spec/comparison.hpp"
#include "imunoise/spec/spec.hpp"
#include "imunoise/study/curves.hpp"
#include "imunoise/study/record.hpp"

namespace imunoise::study {

struct StudyOptions {
  /// Curves to compute; the overlapping Allan deviation is always computed (the fit uses it)
  /// and put first when missing.
  CurveOptions curves;
  fit::FitOptions fit;
  TauGrid fit_grid;                ///< tau grid of the fitted oadev curve (octave)
  std::optional<Spec> spec;        ///< datasheet to compare with
  double nav_hours = 1.0;          ///< duration of the navigation-error curves (h)
  double nav_latitude_deg = 58.5;  ///< latitude of the navigation model (the paper's site)
  /// Navigation models (nav/navigation.hpp names): the physical models (the Schuler closed
  /// forms, the covariance propagation, and the Monte Carlo, 1000 seeded runs, which answers
  /// the same question by simulation); the paper's eq. 6 where it belongs (the demo, or asked for).
  std::string nav_models = "schuler,covariance,montecarlo";
  std::string geometry;            ///< redundant-unit geometry: tetra, 3+1, cone:N:DEG, file ("": none)
  bool keep_going = false;         ///< a failing channel is reported, the others finish
  double kalibr_inflation = 1.0;   ///< factor on the Kalibr values (> 0)
  std::string kalibr_topic = "/imu0";
  std::string title = "imunoise noise study";
};

/// A stage of work, for progress display: what is being done and how far the study is (0..1).
using Progress = std::function<void(std::string_view what, double fraction)>;

/// An input that could not be read (kept so the report names it).
struct FailedInput {
  std::string source;
  std::string error;
};

struct ChannelStudy {
  Record record;                    ///< samples released after the study (phase_si empty)
  std::vector<Curve> curves;
  std::optional<fit::FitResult> fit;
  std::optional<SpecComparison> comparison;
  std::optional<nav::NavResult> nav;  ///< navigation-error curves (none: not computed, see warnings)
  std::string error;                ///< non-empty: this channel failed (keep_going)
  std::vector<std::string> warnings;
};

struct Study {
  StudyOptions options;
  std::vector<ChannelStudy> channels;
  std::vector<FailedInput> failed_inputs;
  /// The redundant unit (geometry given and one fitted gyro per sensor): its analysis, the unit
  /// of its channels and, when run on the samples, the fault detection.
  struct Redundant {
    redundant::Analysis analysis;
    Unit unit;
    std::optional<redundant::DetectionResult> detection;
  };
  std::optional<Redundant> redundant;
  std::vector<Curve> fused_curves;  ///< oadev of the fused body axes x, y, z (from the samples)
  Record fused_record;              ///< rate and unit of the fused axes (no samples kept)
  std::vector<std::string> notes;   ///< study-level remarks (stages not available, ...)
  /// The whole IMU's navigation error, when the study has fitted gyro and accelerometer
  /// channels with units: each channel on its axis (x north, y east, z down) by the last letter
  /// of its name (gyro_x, w_RS_S_y, az), or in the order given when the names do not say.
  struct ImuNavigation {
    nav::NavResult result;
    std::array<std::string, 3> gyro_channels;   ///< per axis ("" : none)
    std::array<std::string, 3> accel_channels;
  };
  std::optional<ImuNavigation> imu;
};

/// Checks that the channels can be studied together (rate and units); InputError naming the
/// two channels and the fix otherwise.
void check_compatible(const std::vector<Record>& records);

/// Runs every stage on every record. `failed` lists inputs the caller could not read (kept in
/// the report). Throws InputError for bad options or, without keep_going, a failing channel.
Study run_study(std::vector<Record> records, const StudyOptions& options,
                std::vector<FailedInput> failed = {}, const Progress& progress = {});

/// The report document: {"title", "version", "inputs", "options", "channels": [{"name",
/// "source", "unit", "quantity", "rate_hz", "n_samples", "duration_s", "curves": [dev JSON],
/// "fit": {fit JSON}, "model": {...}, "spec_comparison", "spec_limits", "nav"}], "redundant",
/// "kalibr", "figures", "notes"}. Every number states its unit (in its key or a "unit" field).
nlohmann::json study_json(const Study& study);

/// The navigation error of a free-inertial system whose three gyros all have the noise `c`
/// (SI), with the study's navigation options (nav_hours, nav_latitude_deg, nav_models): what
/// run_study computes per gyro channel, and study_sensor at the horizon. InputError from the
/// navigation module.
nav::NavResult navigation(const NoiseCoefficients& c, const StudyOptions& options);

/// The library version written into reports.
std::string_view version();

}  // namespace imunoise::study
