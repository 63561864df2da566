#pragma once
// Literal transcriptions of the total, Theo1 and time-error definitions (NIST SP 1065 sec.
// 5.2.11-5.2.17, as documented in total.hpp, theo.hpp, time_error.hpp), in long double and
// deliberately naive (O(N m^2) for mtot/htot, O(N m) for theo1 and MTIE): the fast algorithms
// are checked against them.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace imunoise::test {

inline double reference_totdev(const std::vector<double>& x, double tau0, std::size_t m) {
  const auto N = static_cast<long long>(x.size());
  auto star = [&](long long i) -> long double {
    if (i < 0) return 2.0L * x[0] - x[static_cast<std::size_t>(-i)];
    if (i > N - 1) return 2.0L * x[N - 1] - x[static_cast<std::size_t>(2 * (N - 1) - i)];
    return x[static_cast<std::size_t>(i)];
  };
  const auto mm = static_cast<long long>(m);
  long double sum = 0.0L;
  for (long long i = 1; i <= N - 2; ++i) {
    const long double d = star(i - mm) - 2.0L * star(i) + star(i + mm);
    sum += d * d;
  }
  const long double tau = static_cast<long double>(m) * tau0;
  return static_cast<double>(std::sqrt(sum / (2.0L * (N - 2))) / tau);
}

// sum over subsequences of (1/(6m)) sum_j z_j^2 (see total.hpp), on a sequence u.
inline long double reference_reflected_sum(const std::vector<double>& u, std::size_t m,
                                           std::size_t* count) {
  const std::size_t len = 3 * m;
  const std::size_t h = len / 2;
  long double total = 0.0L;
  *count = 0;
  for (std::size_t n = 0; n + len <= u.size(); ++n, ++*count) {
    long double first = 0.0L, second = 0.0L;
    for (std::size_t i = 0; i < h; ++i) first += u[n + i];
    for (std::size_t i = len - h; i < len; ++i) second += u[n + i];
    const long double slope = (second / h - first / h) / static_cast<long double>(len - h);
    std::vector<long double> y(len);
    for (std::size_t i = 0; i < len; ++i) y[i] = u[n + i] - slope * static_cast<long double>(i);
    std::vector<long double> e;
    for (std::size_t i = len; i-- > 0;) e.push_back(y[i]);
    for (std::size_t i = 0; i < len; ++i) e.push_back(y[i]);
    for (std::size_t i = len; i-- > 0;) e.push_back(y[i]);
    long double inner = 0.0L;
    for (std::size_t j = 0; j < 6 * m; ++j) {
      long double z = 0.0L;
      for (std::size_t k = j; k < j + m; ++k) z += e[k + 2 * m] - 2.0L * e[k + m] + e[k];
      z /= static_cast<long double>(m);
      inner += z * z;
    }
    total += inner / (6.0L * m);
  }
  return total;
}

inline double reference_mtotdev(const std::vector<double>& x, double tau0, std::size_t m) {
  std::size_t count = 0;
  const long double sum = reference_reflected_sum(x, m, &count);
  const long double tau = static_cast<long double>(m) * tau0;
  return static_cast<double>(std::sqrt(sum / (2.0L * count)) / tau);
}

inline double reference_htotdev(const std::vector<double>& x, double tau0, std::size_t m) {
  std::vector<double> y(x.size() - 1);
  for (std::size_t k = 0; k + 1 < x.size(); ++k) y[k] = (x[k + 1] - x[k]) / tau0;
  std::size_t count = 0;
  const long double sum = reference_reflected_sum(y, m, &count);
  return static_cast<double>(std::sqrt(sum / (6.0L * count)));
}

inline double reference_theo1(const std::vector<double>& x, double tau0, std::size_t m) {
  const std::size_t N = x.size();
  const std::size_t k = m / 2;
  long double sum = 0.0L;
  for (std::size_t i = 0; i + m < N; ++i) {
    for (std::size_t d = 0; d < k; ++d) {
      const long double v = (static_cast<long double>(x[i]) - x[i + k - d]) +
                            (static_cast<long double>(x[i + m]) - x[i + k + d]);
      sum += v * v / static_cast<long double>(k - d);
    }
  }
  const long double mt = static_cast<long double>(m) * tau0;
  return static_cast<double>(std::sqrt(sum / (0.75L * (N - m) * mt * mt)));
}

inline double reference_mtie(const std::vector<double>& x, std::size_t m) {
  double worst = 0.0;
  for (std::size_t i = 0; i + m < x.size(); ++i) {
    const auto [lo, hi] = std::minmax_element(x.begin() + static_cast<long>(i),
                                              x.begin() + static_cast<long>(i + m + 1));
    worst = std::max(worst, *hi - *lo);
  }
  return worst;
}

inline double reference_tierms(const std::vector<double>& x, std::size_t m) {
  long double sum = 0.0L;
  for (std::size_t i = 0; i + m < x.size(); ++i) {
    const long double d = static_cast<long double>(x[i + m]) - x[i];
    sum += d * d;
  }
  return static_cast<double>(std::sqrt(sum / (x.size() - m)));
}

}  // namespace imunoise::test
