#include "imunoise/time_error.hpp"

#include <cmath>
#include <vector>

#include "domain_check.hpp"
#include "parallel.hpp"
#include "square_sum.hpp"

namespace imunoise {

std::vector<DevPoint> mtie(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::mtie, phase, tau0_s, factors);
  std::vector<DevPoint> points(factors.size());
  const std::size_t n = phase.size();
  detail::parallel_for(factors.size(), options.threads, [&](std::size_t t) {
    const std::size_t m = factors[t];
    // Ring buffers of indices whose values decrease (max queue) / increase (min queue).
    std::vector<std::size_t> qmax(m + 2);
    std::vector<std::size_t> qmin(m + 2);
    const std::size_t cap = m + 2;
    std::size_t hmax = 0, tmax = 0, hmin = 0, tmin = 0;  // head/tail counters
    double worst = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double v = phase[k];
      while (tmax != hmax && phase[qmax[(tmax - 1) % cap]] <= v) --tmax;
      qmax[tmax % cap] = k;
      ++tmax;
      while (tmin != hmin && phase[qmin[(tmin - 1) % cap]] >= v) --tmin;
      qmin[tmin % cap] = k;
      ++tmin;
      if (k >= m) {  // window x[k-m .. k]
        const std::size_t start = k - m;
        while (qmax[hmax % cap] < start) ++hmax;
        while (qmin[hmin % cap] < start) ++hmin;
        const double range = phase[qmax[hmax % cap]] - phase[qmin[hmin % cap]];
        if (range > worst) worst = range;
      }
    }
    points[t].m = m;
    points[t].tau_s = static_cast<double>(m) * tau0_s;
    points[t].n = n - m;
    points[t].dev = worst;
  });
  return points;
}

std::vector<DevPoint> tierms(std::span<const double> phase, double tau0_s,
                             std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::tierms, phase, tau0_s, factors);
  std::vector<DevPoint> points(factors.size());
  const std::size_t n = phase.size();
  detail::parallel_for(factors.size(), options.threads, [&](std::size_t t) {
    const std::size_t m = factors[t];
    const std::size_t count = n - m;
    const double* x = phase.data();
    const long double sum =
        detail::square_sum4(count, [&](std::size_t i) { return x[i + m] - x[i]; });
    points[t].m = m;
    points[t].tau_s = static_cast<double>(m) * tau0_s;
    points[t].n = count;
    points[t].dev = std::sqrt(static_cast<double>(sum / static_cast<long double>(count)));
  });
  return points;
}

}  // namespace imunoise
