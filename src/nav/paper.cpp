#include "imunoise/nav/paper.hpp"

#include <cmath>

namespace imunoise::nav::paper {

double latitude_rad(double sigma_eps, double t_s, double w0) {
  return sigma_eps / w0 * std::abs(std::cos(w0 * t_s) - 1.0);
}

double longitude_rad(double sigma_eps, double t_s, double w0) {
  return sigma_eps / w0 * std::abs(std::sin(w0 * t_s) - w0 * t_s);
}

double path_m(double sigma_eps, double t_s, double w0, double radius_m) {
  return radius_m * longitude_rad(sigma_eps, t_s, w0);
}

double sigma_eps_for_latitude(double lat_rad, double t_s, double w0) {
  return lat_rad / latitude_rad(1.0, t_s, w0);
}

double sigma_eps_for_longitude(double lon_rad, double t_s, double w0) {
  return lon_rad / longitude_rad(1.0, t_s, w0);
}

double sigma_eps_for_path(double path, double t_s, double w0, double radius_m) {
  return path / path_m(1.0, t_s, w0, radius_m);
}

}  // namespace imunoise::nav::paper
