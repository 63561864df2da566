#pragma once
// ROS sensor_msgs/Imu covariance diagonals (row-major 3x3 arrays), as YAML:
// angular_velocity_covariance (rad^2/s^2) and linear_acceleration_covariance (m^2/s^4) are the
// variance of ONE sample at the IMU rate f: sigma_d^2 = N^2 f. The message has no place for
// the bias random walk or instability (said in a comment).
#include <string>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// An absent sensor's array is a commented placeholder (a -1 in element 0 means "not
/// provided" in the message's own definition; imunoise leaves that choice to the user).
/// Throws InputError without any sensor.
std::string ros_covariance_yaml(const ExportModel& model);

}  // namespace imunoise::exports
