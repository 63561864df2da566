#pragma once
// The noise-model files for a user's filter written from a fit: Kalibr's imu.yaml and the
// Kalman-filter parameters (exports.hpp renders them). Every target is checked before any is
// written, and an existing file is never replaced without `force`.
#include <string>

#include "imunoise/noise_coefficients.hpp"

namespace imunoise {

struct ExportRequest {
  std::string kalibr_path;             ///< Kalibr imu.yaml ("": none)
  std::string kf_json_path;            ///< Kalman-filter parameters as JSON ("": none)
  double inflation = 1.0;              ///< factor on the Kalibr values (> 0), stated in the file
  std::string kalibr_topic = "/imu0";  ///< rostopic written to imu.yaml
  bool force = false;                  ///< replace existing files
};

/// InputError for a target that exists (without force), is "-", names the same file twice, or
/// a Kalibr file asked of an accelerometer fit. `rate_hz`: the record's sample rate, for
/// update_rate and the discrete values.
void write_exports(const ExportRequest& request, const NoiseCoefficients& coefficients, double rate_hz);

}  // namespace imunoise
