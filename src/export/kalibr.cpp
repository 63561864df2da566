#include "imunoise/export/kalibr.hpp"

#include "imunoise/spec/exports.hpp"
#include "text.hpp"

namespace imunoise::exports {

std::string kalibr_yaml(const ExportModel& model) {
  check_export_model(model, "--export kalibr");
  detail::require_gyro(model, "kalibr");
  const NoiseCoefficients* accel = model.accel ? &model.accel->coefficients : nullptr;
  return detail::measured_header(model, "Kalibr imu.yaml", "#") + "\n" +
         kalibr_imu_yaml(model.gyro->coefficients, accel, model.rate_hz, model.inflation, model.topic);
}

}  // namespace imunoise::exports
