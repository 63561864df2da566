#pragma once
// The paper's eq. 6, as published (paper.md; the magnitudes are meant):
//   sigma_lat(t)  = (sigma_eps / w0) |cos(w0 t) - 1|           latitude (rad)
//   sigma_S(t)    = (sigma_eps R / w0) |sin(w0 t) - w0 t|      path (m)
//   sigma_lon(t)  = (sigma_eps / w0) |sin(w0 t) - w0 t|        longitude (rad)
// with w0 = sqrt(g / R). The latitude line has the velocity-error shape, not the drift's
// latitude response (schuler.hpp), and the paper does not say what sigma_eps is. Its published
// longitude, 3.9 deg at 1 h, follows from sigma_eps = 8.9e-4 deg/s: gyro 1's N (8.9e-4
// deg/sqrt(s), Table 2) read as a rate; the same sigma_eps gives 0.894 deg and 434 km for the
// other two lines, not the published 0.37 deg and 22.6 km (docs/navigation.md).
namespace imunoise::nav::paper {

double latitude_rad(double sigma_eps_rad_s, double t_s, double w0_rad_s);
double path_m(double sigma_eps_rad_s, double t_s, double w0_rad_s, double radius_m);
double longitude_rad(double sigma_eps_rad_s, double t_s, double w0_rad_s);

/// The sigma_eps (rad/s) each line needs to give `value` at t_s: inverts the three lines.
double sigma_eps_for_latitude(double lat_rad, double t_s, double w0_rad_s);
double sigma_eps_for_path(double path_m, double t_s, double w0_rad_s, double radius_m);
double sigma_eps_for_longitude(double lon_rad, double t_s, double w0_rad_s);

}  // namespace imunoise::nav::paper
