#include "imunoise/deviation.hpp"

#include <cmath>
#include <string>

#include "difference_sums.hpp"
#include "domain_check.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/hadamard.hpp"
#include "imunoise/modified_allan.hpp"
#include "imunoise/theo.hpp"
#include "imunoise/time_error.hpp"
#include "imunoise/total.hpp"

#include "prefaulted.hpp"

namespace imunoise {
namespace {

// sigma = sqrt(sum_sq / (divisor * n)) / tau, the shape shared by every estimator here.
std::vector<DevPoint> scale(const detail::DifferenceSums& sums, double tau0_s,
                            std::span<const std::size_t> factors, double divisor,
                            bool modified) {
  std::vector<DevPoint> points;  // every tau of a long record: tens of MB, mapped in bulk
  detail::resize_prefaulted(points, factors.size());
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const double m = static_cast<double>(factors[t]);
    const double tau_s = m * tau0_s;
    const double n = static_cast<double>(sums.n[t]);
    const double norm = modified ? divisor * n * m * m : divisor * n;
    points[t].m = factors[t];
    points[t].tau_s = tau_s;
    points[t].n = sums.n[t];
    points[t].dev = std::sqrt(sums.sum_sq[t] / norm) / tau_s;
  }
  return points;
}

}  // namespace

std::vector<DevPoint> adev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions&) {
  detail::check_factors(Estimator::adev, phase, tau0_s, factors);
  return scale(detail::strided_difference_sums(phase, 2, factors), tau0_s, factors, 2.0, false);
}

std::vector<DevPoint> oadev(std::span<const double> phase, double tau0_s,
                            std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::oadev, phase, tau0_s, factors);
  return scale(detail::overlapping_difference_sums(phase, 2, factors, options.threads), tau0_s,
               factors, 2.0, false);
}

std::vector<DevPoint> mdev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::mdev, phase, tau0_s, factors);
  return scale(detail::modified_difference_sums(phase, factors, options.threads), tau0_s,
               factors, 2.0, true);
}

std::vector<DevPoint> tdev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options) {
  auto points = mdev(phase, tau0_s, factors, options);
  for (auto& point : points) point.dev *= point.tau_s / std::sqrt(3.0);
  return points;
}

std::vector<DevPoint> hdev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions&) {
  detail::check_factors(Estimator::hdev, phase, tau0_s, factors);
  return scale(detail::strided_difference_sums(phase, 3, factors), tau0_s, factors, 6.0, false);
}

std::vector<DevPoint> ohdev(std::span<const double> phase, double tau0_s,
                            std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::ohdev, phase, tau0_s, factors);
  return scale(detail::overlapping_difference_sums(phase, 3, factors, options.threads), tau0_s,
               factors, 6.0, false);
}

std::vector<DevPoint> compute_deviation(Estimator estimator, std::span<const double> phase,
                                        double tau0_s, std::span<const std::size_t> factors,
                                        const DevOptions& options) {
  switch (estimator) {
    case Estimator::adev: return adev(phase, tau0_s, factors, options);
    case Estimator::oadev: return oadev(phase, tau0_s, factors, options);
    case Estimator::mdev: return mdev(phase, tau0_s, factors, options);
    case Estimator::tdev: return tdev(phase, tau0_s, factors, options);
    case Estimator::hdev: return hdev(phase, tau0_s, factors, options);
    case Estimator::ohdev: return ohdev(phase, tau0_s, factors, options);
    case Estimator::totdev: return totdev(phase, tau0_s, factors, options);
    case Estimator::mtotdev: return mtotdev(phase, tau0_s, factors, options);
    case Estimator::ttotdev: return ttotdev(phase, tau0_s, factors, options);
    case Estimator::htotdev: return htotdev(phase, tau0_s, factors, options);
    case Estimator::theo1: return theo1(phase, tau0_s, factors, options);
    case Estimator::theobr: return theobr(phase, tau0_s, factors, options);
    case Estimator::mtie: return mtie(phase, tau0_s, factors, options);
    case Estimator::tierms: return tierms(phase, tau0_s, factors, options);
  }
  throw InputError("unsupported estimator");
}

}  // namespace imunoise
