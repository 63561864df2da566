#include "term_split.hpp"

#include <fmt/core.h>

#include "error_model.hpp"

namespace imunoise::nav::detail {
namespace {

// One noise term kept (all axes), the others zeroed: term j of Q N B K R GM bias.
GyroTerms only(const GyroTerms& t, int j) {
  GyroTerms o;
  switch (j) {
    case 0: o.q_rad = t.q_rad; break;
    case 1: o.n_rad_sqrt_s = t.n_rad_sqrt_s; break;
    case 2: o.b_rad_s = t.b_rad_s; break;
    case 3: o.k_rad_s_sqrt_s = t.k_rad_s_sqrt_s; break;
    case 4: o.r_rad_s2 = t.r_rad_s2; break;
    case 5: o.gauss_markov = t.gauss_markov; break;
    default: o.bias_rad_s = t.bias_rad_s; break;
  }
  return o;
}

AccelTerms only(const AccelTerms& t, int j) {
  AccelTerms o;
  switch (j) {
    case 0: o.q_m_s = t.q_m_s; break;
    case 1: o.n_m_s_sqrt_s = t.n_m_s_sqrt_s; break;
    case 2: o.b_m_s2 = t.b_m_s2; break;
    case 3: o.k_m_s2_sqrt_s = t.k_m_s2_sqrt_s; break;
    case 4: o.r_m_s3 = t.r_m_s3; break;
    case 5: o.gauss_markov = t.gauss_markov; break;
    default: o.bias_m_s2 = t.bias_m_s2; break;
  }
  return o;
}


bool any(const SensorTerms& t) {
  return t.q != 0 || t.n != 0 || t.b != 0 || t.k != 0 || t.r != 0 || gauss_markov_rss(t.gauss_markov) != 0 || t.bias != 0;
}

}  // namespace

std::vector<TermPart> split_terms(const std::array<GyroTerms, 3>& gyro, const std::array<AccelTerms, 3>& accel) {
  constexpr const char* kTermNames[] = {"Q", "N", "B", "K", "R", "GM", "bias"};
  std::vector<TermPart> parts;
  for (int j = 0; j < 7; ++j) {
    TermPart g{fmt::format("gyro {}", kTermNames[j])}, a{fmt::format("accel {}", kTermNames[j])};
    bool gyro_term = false, accel_term = false;
    for (std::size_t i = 0; i < 3; ++i) {
      g.gyro[i] = only(gyro[i], j);
      gyro_term = gyro_term || any(sensor_terms(g.gyro[i]));
      if (i < 2) {
        a.accel[i] = only(accel[i], j);
        accel_term = accel_term || any(sensor_terms(a.accel[i]));
      }
    }
    if (gyro_term) parts.push_back(std::move(g));
    if (accel_term) parts.push_back(std::move(a));
  }
  return parts;
}

}  // namespace imunoise::nav::detail
