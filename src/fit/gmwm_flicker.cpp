// Flicker noise as a fixed sum of AR1 terms (include/imunoise/fit/gmwm_flicker.hpp).
#include "imunoise/fit/gmwm_flicker.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/fit/gmwm.hpp"
#include "gmwm_detail.hpp"

namespace imunoise::fit {
namespace {

constexpr double kAr1PeakRatio = 1.89262;  // tau of the AR1 Allan peak / T_c
constexpr int kChecksPerOctave = 8;

/// Averaging factors 2^(j / 8) over [m_lo, m_hi], rounded, without repeats.
std::vector<std::size_t> check_factors(std::size_t m_lo, std::size_t m_hi) {
  std::vector<std::size_t> out;
  const double octaves = std::log2(static_cast<double>(m_hi) / static_cast<double>(m_lo));
  const int steps = static_cast<int>(std::ceil(octaves * kChecksPerOctave - 1e-9));
  for (int j = 0; j <= steps; ++j) {
    const double m = static_cast<double>(m_lo) * std::pow(2.0, std::min(octaves, j / double(kChecksPerOctave)));
    const auto mi = std::clamp<std::size_t>(static_cast<std::size_t>(std::llround(m)), m_lo, m_hi);
    if (out.empty() || out.back() != mi) out.push_back(mi);
  }
  return out;
}

}  // namespace

FlickerMixture flicker_ar1_mixture(double tau0_s, std::size_t m_lo, std::size_t m_hi, int per_decade) {
  if (!(tau0_s > 0.0) || m_lo < 1 || m_hi < m_lo) {
    throw InputError("flicker mixture: needs tau0 > 0 and averaging factors 1 <= m_lo <= m_hi");
  }
  if (per_decade < 1 || per_decade > 4) {
    throw InputError("flicker mixture: 1 to 4 Gauss-Markov terms per decade");
  }
  const double target = gmwm_avar_flicker(1.0);
  const double t_lo = static_cast<double>(m_lo) * tau0_s / kAr1PeakRatio;
  const double t_hi = static_cast<double>(m_hi) * tau0_s / kAr1PeakRatio;
  // One decade beyond each end of the span, so that the ends are flat too.
  const int last = static_cast<int>(std::ceil(std::log10(t_hi / t_lo) * per_decade - 1e-9)) + per_decade;
  std::vector<double> times;
  for (int i = -per_decade; i <= last; ++i) times.push_back(t_lo * std::pow(10.0, static_cast<double>(i) / per_decade));
  const auto ms = check_factors(m_lo, m_hi);
  detail::Matrix a(static_cast<Eigen::Index>(ms.size()), static_cast<Eigen::Index>(times.size()));
  for (std::size_t r = 0; r < ms.size(); ++r) {
    for (std::size_t c = 0; c < times.size(); ++c) {
      a(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = gmwm_avar_ar1(times[c], tau0_s, ms[r]) / target;
    }
  }
  const detail::Vector w = detail::nnls_lh(a, detail::Vector::Ones(a.rows()));
  FlickerMixture out;
  out.m_lo = m_lo;
  out.m_hi = m_hi;
  out.per_decade = per_decade;
  for (std::size_t c = 0; c < times.size(); ++c) {
    const double wc = w(static_cast<Eigen::Index>(c));
    if (wc > 0.0) {
      out.correlation_time_s.push_back(times[c]);
      out.variance_per_b2.push_back(wc);
    }
  }
  if (out.empty()) throw InputError("flicker mixture: no Gauss-Markov term fits the span");
  for (std::size_t m : ms) {
    out.ripple = std::max(out.ripple, std::abs(gmwm_avar_flicker_mixture(out, tau0_s, m) / target - 1.0));
  }
  return out;
}

double gmwm_avar_flicker_mixture(const FlickerMixture& mixture, double tau0_s, std::size_t m) {
  double sum = 0.0;
  for (std::size_t i = 0; i < mixture.correlation_time_s.size(); ++i) {
    sum += mixture.variance_per_b2[i] * gmwm_avar_ar1(mixture.correlation_time_s[i], tau0_s, m);
  }
  return sum;
}

}  // namespace imunoise::fit
