#include "imunoise/spec/write_exports.hpp"

#include <filesystem>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "imunoise/error.hpp"
#include "imunoise/io/atomic_output.hpp"
#include "imunoise/spec/exports.hpp"
#include "imunoise/units.hpp"

namespace imunoise {
namespace {

void check_target(const std::string& option, const std::string& path, bool force) {
  if (path == "-") {
    throw InputError(option +
                     " -: the export needs a file name (standard output carries the "
                     "command's report); fix: pass " +
                     option + " FILE");
  }
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !force) {
    throw InputError(path + ": file exists; imunoise does not overwrite it — choose another " +
                     option + " name or pass --force");
  }
}

void write_file(const std::string& path, bool force, const std::string& text) {
  io::AtomicOutput out(path, force);
  out.write(text.data(), text.size());
  out.commit();
}

}  // namespace

void write_exports(const ExportRequest& request, const NoiseCoefficients& coefficients, double rate_hz) {
  // Everything that can fail is checked before anything is written.
  if (!request.kalibr_path.empty()) {
    check_target("--kalibr", request.kalibr_path, request.force);
    if (coefficients.quantity != Quantity::angular_rate) {
      throw InputError("--kalibr: the fit is of " + std::string(quantity_name(coefficients.quantity)) +
                       "; the Kalibr file is written from a gyro fit (its accelerometer keys are "
                       "left as placeholders); fix: run the fit on a gyro channel");
    }
  }
  if (!request.kf_json_path.empty()) check_target("--kf-json", request.kf_json_path, request.force);
  if (!request.kalibr_path.empty() && request.kalibr_path == request.kf_json_path) {
    throw InputError("--kalibr and --kf-json name the same file '" + request.kalibr_path +
                     "'; fix: give two different file names");
  }
  std::string kalibr_text;
  std::string kf_text;
  if (!request.kalibr_path.empty()) {
    kalibr_text = kalibr_imu_yaml(coefficients, nullptr, rate_hz, request.inflation, request.kalibr_topic);
  }
  if (!request.kf_json_path.empty()) kf_text = kalman_parameters(coefficients, rate_hz).dump(1) + "\n";
  if (!kalibr_text.empty()) write_file(request.kalibr_path, request.force, kalibr_text);
  if (!kf_text.empty()) write_file(request.kf_json_path, request.force, kf_text);
}

}  // namespace imunoise
