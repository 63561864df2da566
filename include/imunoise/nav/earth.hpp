#pragma once
// The Earth constants of the navigation-error models. The paper (eq. 6) and references.md use
// R = 6.380e6 m and g = 9.81 m/s^2, hence the Schuler frequency w0 = sqrt(g / R) =
// 1.24001e-3 rad/s (period 84.45 min); the acceptance figures (135.5 km, 8.33 km, ...) are
// computed with them, so they are the defaults here.
namespace imunoise::nav {

struct EarthModel {
  double radius_m = 6.380e6;        ///< mean Earth radius R (m)
  double gravity_m_s2 = 9.81;       ///< gravity g (m/s^2)
  double rotation_rad_s = 7.292115e-5;  ///< Earth rate Omega (rad/s, WGS-84)
};

}  // namespace imunoise::nav
