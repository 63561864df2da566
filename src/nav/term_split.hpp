#pragma once
// Internal: the noise of the whole IMU split into its terms (gyro N on every axis, accel bias
// on every axis, ...), one part each, for the error budget: the covariance is linear in each
// term's intensity, so the parts' variances add up to the whole.
#include <array>
#include <string>
#include <vector>

#include "imunoise/nav/navigation.hpp"

namespace imunoise::nav::detail {

struct TermPart {
  std::string name;  ///< "gyro N", "accel bias", ...
  std::array<GyroTerms, 3> gyro{};
  std::array<AccelTerms, 3> accel{};
};

/// One part per term present on some axis (the down accelerometer, which no model uses, left
/// out), in the order Q N B K R GM bias, gyros before accelerometers.
std::vector<TermPart> split_terms(const std::array<GyroTerms, 3>& gyro, const std::array<AccelTerms, 3>& accel);

}  // namespace imunoise::nav::detail
