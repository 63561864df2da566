#include "imunoise/export/target_keys.hpp"

#include <cmath>

namespace imunoise::exports {

const std::vector<KeySpec>& target_keys(Target target) {
  using S = Sensor;
  using T = Term;
  using F = Form;
  static const std::vector<KeySpec> kalibr{
      {"gyroscope_noise_density", S::gyro, T::white, F::density, "rad/s/sqrt(Hz)"},
      {"gyroscope_random_walk", S::gyro, T::walk, F::density, "rad/s^2/sqrt(Hz)"},
      {"accelerometer_noise_density", S::accel, T::white, F::density, "m/s^2/sqrt(Hz)"},
      {"accelerometer_random_walk", S::accel, T::walk, F::density, "m/s^3/sqrt(Hz)"}};
  static const std::vector<KeySpec> vins{{"gyr_n", S::gyro, T::white, F::discrete_imu, "rad/s"},
                                         {"gyr_w", S::gyro, T::walk, F::discrete_imu, "rad/s^2"},
                                         {"acc_n", S::accel, T::white, F::discrete_imu, "m/s^2"},
                                         {"acc_w", S::accel, T::walk, F::discrete_imu, "m/s^3"}};
  static const std::vector<KeySpec> orbslam3{{"IMU.NoiseGyro", S::gyro, T::white, F::density, "rad/s/sqrt(Hz)"},
                                             {"IMU.GyroWalk", S::gyro, T::walk, F::density, "rad/s^2/sqrt(Hz)"},
                                             {"IMU.NoiseAcc", S::accel, T::white, F::density, "m/s^2/sqrt(Hz)"},
                                             {"IMU.AccWalk", S::accel, T::walk, F::density, "m/s^3/sqrt(Hz)"}};
  static const std::vector<KeySpec> gtsam{
      {"gyroscopeCovariance", S::gyro, T::white, F::psd, "rad^2/s^2/Hz"},
      {"biasOmegaCovariance", S::gyro, T::walk, F::psd, "rad^2/s^4/Hz"},
      {"accelerometerCovariance", S::accel, T::white, F::psd, "m^2/s^4/Hz"},
      {"biasAccCovariance", S::accel, T::walk, F::psd, "m^2/s^6/Hz"}};
  static const std::vector<KeySpec> px4{{"EKF2_GYR_NOISE", S::gyro, T::white, F::discrete_ekf, "rad/s"},
                                        {"EKF2_GYR_B_NOISE", S::gyro, T::walk, F::discrete_ekf, "rad/s^2"},
                                        {"EKF2_ACC_NOISE", S::accel, T::white, F::discrete_ekf, "m/s^2"},
                                        {"EKF2_ACC_B_NOISE", S::accel, T::walk, F::discrete_ekf, "m/s^3"}};
  static const std::vector<KeySpec> matlab{
      {"gyro.NoiseDensity", S::gyro, T::white, F::density, "(rad/s)/sqrt(Hz)"},
      {"gyro.RandomWalk", S::gyro, T::walk, F::density, "(rad/s)*sqrt(Hz)"},
      {"accel.NoiseDensity", S::accel, T::white, F::density, "(m/s^2)/sqrt(Hz)"},
      {"accel.RandomWalk", S::accel, T::walk, F::density, "(m/s^2)*sqrt(Hz)"}};
  static const std::vector<KeySpec> ros{
      {"angular_velocity_covariance", S::gyro, T::white, F::variance_imu, "rad^2/s^2"},
      {"linear_acceleration_covariance", S::accel, T::white, F::variance_imu, "m^2/s^4"}};
  switch (target) {
    case Target::kalibr:
    case Target::openvins: return kalibr;
    case Target::vins: return vins;
    case Target::orbslam3: return orbslam3;
    case Target::gtsam: return gtsam;
    case Target::px4: return px4;
    case Target::matlab: return matlab;
    case Target::ros: return ros;
  }
  return kalibr;
}

double file_value(Form form, double c, double rate_hz, double ekf_rate_hz) {
  switch (form) {
    case Form::density: return c;
    case Form::discrete_imu: return c * std::sqrt(rate_hz);
    case Form::discrete_ekf: return c * std::sqrt(ekf_rate_hz);
    case Form::psd: return c * c;
    case Form::variance_imu: return c * c * rate_hz;
  }
  return c;
}

std::string form_formula(Form form, Term term) {
  const std::string c = term == Term::white ? "N" : "K";
  switch (form) {
    case Form::density: return c;
    case Form::discrete_imu: return c + " sqrt(f)";
    case Form::discrete_ekf: return c + " sqrt(f_ekf)";
    case Form::psd: return c + "^2";
    case Form::variance_imu: return c + "^2 f";
  }
  return c;
}

}  // namespace imunoise::exports
