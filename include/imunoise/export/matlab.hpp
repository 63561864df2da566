#pragma once
// MATLAB gyroparams / accelparams (Navigation / Sensor Fusion toolboxes) as a .m script:
// NoiseDensity = N ((rad/s)/sqrt(Hz); accel (m/s^2)/sqrt(Hz)), RandomWalk = K
// ((rad/s) sqrt(Hz); accel (m/s^2) sqrt(Hz)), BiasInstability = B (rad/s; m/s^2),
// NoiseType "double-sided" (imunoise's N is the square root of the two-sided PSD). imuSensor
// discretises at its SampleRate f: white std N sqrt(f), walk step K / sqrt(f).
#include <string>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// Absent terms are commented placeholders. Throws InputError without any sensor.
std::string matlab_script(const ExportModel& model);

}  // namespace imunoise::exports
