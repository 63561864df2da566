#pragma once
// A GNSS outage: how far an aided system drifts from the moment its aiding stops. The
// covariance model (error_model.hpp) starts from the errors the aiding left, 1-sigma and
// independent per axis (position, velocity, attitude; 0 allowed: a perfectly aided start), and
// the sensors' noise states at their full prior (a bias is not taken as calibrated by the
// aiding: conservative), and is propagated to each horizon. Per horizon: the 1-sigma north and
// east position error, the horizontal RMS radial error, the RMS horizontal velocity error, the
// RMS attitude error (tilt and heading) and the error budget: each term's share of the
// horizontal position variance (the covariance is linear in each term's intensity and in the
// initial errors, so the shares are exact and sum to 1).
#include <array>
#include <vector>

#include "imunoise/nav/navigation.hpp"

namespace imunoise::nav {

/// The outage errors at options.outage_s (each a whole number of dt_s steps). Throws
/// InputError for a horizon that is not positive or not a multiple of dt_s.
std::vector<OutagePoint> outage_errors(const NavOptions& options, const std::array<GyroTerms, 3>& gyro,
                                       const std::array<AccelTerms, 3>& accel);

}  // namespace imunoise::nav
