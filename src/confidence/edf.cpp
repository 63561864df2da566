#include "imunoise/confidence/edf.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "imunoise/error.hpp"
#include "power_law_model.hpp"

namespace imunoise {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Truncation of the autocovariance sum (the paper's J_max).
constexpr std::size_t kJmax = 100;

// ---------------------------------------------------------------------------------------------
// The model. Time is measured in units of tau. w(t) is a continuous-time power-law process whose
// generalized autocovariance is sw(t); phase x is F times the first difference of w over 1/F
// (F = m: phase samples as tau0-averages; F = 1: phase averaged over tau, the modified
// variances); z is the d-th difference of x with lag 1. The EDF of the time average of M values
// of z^2 taken with stride 1/S follows from the autocovariance sz of z (Isserlis):
//   1/edf = (1 / (M sz(0)^2)) * sum_{|j|<M} (1 - |j|/M) sz(j/S)^2.
// ---------------------------------------------------------------------------------------------

// Generalized autocovariance of w for integer alpha in -4..2 (paper eq. 7; 0 ln 0 = 0).
double sw(double t, int alpha) {
  const double a = std::fabs(t);
  // Only the flicker types need the logarithm (most of an EDF's time when taken for all).
  const auto log_a = [a] { return a > 0.0 ? std::log(a) : 0.0; };
  switch (alpha) {
    case 2:
      return -a;
    case 1:
      return a * a * log_a();
    case 0:
      return a * a * a;
    case -1:
      return -a * a * a * a * log_a();
    case -2:
      return -std::pow(a, 5);
    case -3:
      return std::pow(a, 6) * log_a();
    case -4:
      return std::pow(a, 7);
    default:
      return kNaN;
  }
}

// -F^2 times the central second difference of t^2 ln|t| with step h = 1/F, for |t| >= 8h,
// from its Taylor series (the direct difference loses ~2 log10(F |t|) digits to cancellation):
//   F^2 [2g(t) - g(t-h) - g(t+h)] = -(2 ln|t| + 3) + sum_{k>=2} 4 u^(k-1) / ((2k)(2k-1)(2k-2)),
// u = (h/t)^2 <= 1/64, since g^(2k)(t) = -2 (2k-3)! / t^(2k-2) for k >= 2. Ten terms reach
// double precision.
double sx_flicker_pm_far(double t, double F) {
  const double u = 1.0 / (F * F * t * t);
  double sum = 0.0;
  double power = 1.0;
  for (int k = 2; k <= 11; ++k) {
    power *= u;
    const double kk = 2.0 * k;
    sum += 4.0 * power / (kk * (kk - 1.0) * (kk - 2.0));
  }
  return -(2.0 * std::log(std::fabs(t)) + 3.0) + sum;
}

// Autocovariance of the phase (paper eq. 8). F = infinity: the tau0 filter is dropped.
double sx(double t, double F, int alpha) {
  if (std::isinf(F)) return sw(t, alpha + 2);  // used for alpha <= 0 only
  if (alpha == 1 && std::fabs(t) * F >= 8.0) return sx_flicker_pm_far(t, F);
  const double h = 1.0 / F;
  return F * F * (2.0 * sw(t, alpha) - sw(t - h, alpha) - sw(t + h, alpha));
}

// Binomial coefficient C(n, k) for the small n used here (n <= 12: 4d with d <= 3), from a
// table: sz runs it 2d + 1 times per lag, a hundred lags per EDF, an EDF per tau.
constexpr double binomial_product(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

constexpr int kMaxBinomialN = 12;
constexpr auto kBinomials = [] {
  std::array<std::array<double, kMaxBinomialN + 1>, kMaxBinomialN + 1> table{};
  for (int n = 0; n <= kMaxBinomialN; ++n) {
    for (int k = 0; k <= n; ++k) table[n][k] = binomial_product(n, k);
  }
  return table;
}();

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  if (n <= kMaxBinomialN) return kBinomials[static_cast<std::size_t>(n)][static_cast<std::size_t>(k)];
  return binomial_product(n, k);
}

// Autocovariance of z, the d-th difference of x (paper eq. 9):
//   sz(t) = sum_{k=-d..d} (-1)^k C(2d, d+k) sx(t + k).
double sz(double t, double F, int alpha, int d) {
  double sum = 0.0;
  for (int k = -d; k <= d; ++k) {
    const double sign = (k % 2 == 0) ? 1.0 : -1.0;
    sum += sign * binomial(2 * d, d + k) * sx(t + k, F, alpha);
  }
  return sum;
}

}  // namespace

double detail::power_law_sz(double t, double F, int alpha, int d) { return sz(t, F, alpha, d); }

namespace {

// The paper's BasicSum(J, M, S, F, alpha, d) (eq. 10):
//   sz(0)^2 + (1 - J/M) sz(J/S)^2 + 2 sum_{j=1}^{J-1} (1 - j/M) sz(j/S)^2.
double basic_sum(double J, double M, double S, double F, int alpha, int d) {
  const double z0 = sz(0.0, F, alpha, d);
  const double zJ = sz(J / S, F, alpha, d);
  double sum = z0 * z0 + (1.0 - J / M) * zJ * zJ;
  const auto last = static_cast<std::size_t>(J);
  for (std::size_t j = 1; j < last; ++j) {
    const double jj = static_cast<double>(j);
    const double z = sz(jj / S, F, alpha, d);
    sum += 2.0 * (1.0 - jj / M) * z * z;
  }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// The paper's tables: 1/edf ~ (a0 - a1/r)/r for large r = M/S and J > J_max. Rows alpha = 2..-4,
// columns d = 1, 2, 3; NaN where alpha + 2d <= 1. tests/confidence/test_edf.cpp recomputes them
// from their definition, a0 = 2 int_0^{d+1} rho(t)^2 dt and a1 = 2 int_0^{d+1} t rho(t)^2 dt.
// ---------------------------------------------------------------------------------------------
struct TableEntry {
  double a0;
  double a1;
};
constexpr TableEntry kNone{kNaN, kNaN};

// Table 1: modified variances (F = 1).
constexpr std::array<std::array<TableEntry, 3>, 7> kTable1{{
    {{{0.66667, 0.33333}, {0.77778, 0.5}, {0.88000, 0.66667}}},  // alpha = 2
    {{{0.840, 0.345}, {0.997, 0.616}, {1.141, 0.843}}},          // alpha = 1
    {{{1.079, 0.368}, {1.033, 0.607}, {1.184, 0.848}}},          // alpha = 0
    {{kNone, {1.048, 0.534}, {1.180, 0.816}}},                   // alpha = -1
    {{kNone, {1.302, 0.535}, {1.175, 0.777}}},                   // alpha = -2
    {{kNone, kNone, {1.194, 0.703}}},                            // alpha = -3
    {{kNone, kNone, {1.489, 0.702}}},                            // alpha = -4
}};

// Table 2: unmodified variances (F = m); for alpha = 1 the sums are not normalized by sz(0)^2.
constexpr std::array<std::array<TableEntry, 3>, 7> kTable2{{
    {{{1.50000, 0.5}, {1.94444, 1.0}, {2.31000, 1.5}}},          // alpha = 2
    {{{78.6, 25.2}, {790.0, 410.0}, {9950.0, 6520.0}}},          // alpha = 1
    {{{0.66667, 0.16667}, {0.66667, 0.33333}, {0.77778, 0.5}}},  // alpha = 0
    {{kNone, {0.852, 0.375}, {0.997, 0.617}}},                   // alpha = -1
    {{kNone, {1.079, 0.368}, {1.033, 0.607}}},                   // alpha = -2
    {{kNone, kNone, {1.053, 0.553}}},                            // alpha = -3
    {{kNone, kNone, {1.302, 0.535}}},                            // alpha = -4
}};

// Table 3: flicker PM, unmodified: sz(0) ~ b0 + b1 ln m (exactly 2 c0 ln m + ..., see docs).
constexpr std::array<TableEntry, 3> kTable3{{{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}}};

TableEntry table_entry(const std::array<std::array<TableEntry, 3>, 7>& table, int alpha, int d) {
  return table[static_cast<std::size_t>(2 - alpha)][static_cast<std::size_t>(d - 1)];
}

// The initial steps shared by both versions (paper section 3.4), in exact integer arithmetic.
struct Setup {
  double m = 0, F = 0, S = 0, M = 0, J = 0, r = 0;
  bool valid = false;
};

Setup setup(int alpha, const DifferenceVariance& v, std::size_t m, std::size_t n_phase) {
  Setup s;
  if (m == 0 || v.d < 1 || v.d > 3 || alpha < kMinNoiseAlpha || alpha > kMaxNoiseAlpha ||
      alpha + 2 * v.d <= 1) {
    return s;
  }
  const std::size_t d = static_cast<std::size_t>(v.d);
  const std::size_t length = (v.modified ? m : 1) + m * d;  // L = m/F + m d
  if (n_phase < length) return s;
  // M = 1 + floor(S (N - L) / m), S = m (overlapped) or 1.
  const std::size_t count = 1 + (v.overlapping ? n_phase - length : (n_phase - length) / m);
  const std::size_t stride_factor = v.overlapping ? m : 1;
  s.m = static_cast<double>(m);
  s.F = v.modified ? 1.0 : s.m;
  s.S = static_cast<double>(stride_factor);
  s.M = static_cast<double>(count);
  s.J = static_cast<double>(std::min(count, (d + 1) * stride_factor));
  s.r = s.M / s.S;
  s.valid = true;
  return s;
}

}  // namespace

std::string_view noise_type_name(int alpha) {
  switch (alpha) {
    case 2:
      return "white PM";
    case 1:
      return "flicker PM";
    case 0:
      return "white FM";
    case -1:
      return "flicker FM";
    case -2:
      return "random-walk FM";
    case -3:
      return "flicker-walk FM";
    case -4:
      return "random-run FM";
    default:
      return "unknown";
  }
}

std::string_view noise_type_abbreviation(int alpha) {
  switch (alpha) {
    case 2:
      return "WHPM";
    case 1:
      return "FLPM";
    case 0:
      return "WHFM";
    case -1:
      return "FLFM";
    case -2:
      return "RWFM";
    case -3:
      return "FWFM";
    case -4:
      return "RRFM";
    default:
      return "unknown";
  }
}

int parse_noise_type(std::string_view text) {
  std::string lower;
  for (char c : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static constexpr std::array<std::pair<std::string_view, int>, 11> kNames{{{"whpm", 2},
                                                                            {"wpm", 2},
                                                                            {"flpm", 1},
                                                                            {"fpm", 1},
                                                                            {"whfm", 0},
                                                                            {"wfm", 0},
                                                                            {"flfm", -1},
                                                                            {"ffm", -1},
                                                                            {"rwfm", -2},
                                                                            {"fwfm", -3},
                                                                            {"rrfm", -4}}};
  for (const auto& [name, alpha] : kNames) {
    if (lower == name) return alpha;
  }
  static constexpr std::array<std::string_view, 7> kIntegers{"2", "1", "0", "-1", "-2", "-3", "-4"};
  const bool plus = !lower.empty() && lower.front() == '+';
  const std::string_view number =
      plus ? std::string_view(lower).substr(1) : std::string_view(lower);
  for (std::size_t i = 0; i < kIntegers.size(); ++i) {
    if (number == kIntegers[i] && !(plus && i >= 3)) return 2 - static_cast<int>(i);
  }
  throw InputError("unknown noise type '" + std::string(text) +
                   "': give alpha as an integer from -4 to 2 or a name: WHPM (2), FLPM (1), "
                   "WHFM (0), FLFM (-1), RWFM (-2), FWFM (-3), RRFM (-4)");
}

std::string_view edf_method_name(EdfMethod method) {
  switch (method) {
    case EdfMethod::greenhall_riley:
      return "greenhall-riley";
    case EdfMethod::sp1065:
      return "sp1065";
    case EdfMethod::ieee952_simple:
      return "ieee952-simple";
    case EdfMethod::not_available:
      return "not-available";
  }
  return "not-available";
}

std::optional<DifferenceVariance> difference_variance(Estimator estimator) {
  switch (estimator) {
    case Estimator::adev:
      return DifferenceVariance{2, false, false};
    case Estimator::oadev:
      return DifferenceVariance{2, false, true};
    case Estimator::mdev:
    case Estimator::tdev:
      return DifferenceVariance{2, true, true};
    case Estimator::hdev:
      return DifferenceVariance{3, false, false};
    case Estimator::ohdev:
      return DifferenceVariance{3, false, true};
    default:
      break;
      // Hook: totdev, mtotdev, ttotdev, htotdev, theo1, mtie, tierms are not finite-difference
      // variances of this kind; they return nullopt and get their EDF in edf() below.
  }
  return std::nullopt;
}

std::optional<Estimator> finite_difference_proxy(Estimator estimator) {
  switch (estimator) {
    case Estimator::totdev:
    case Estimator::theo1:
    case Estimator::theobr:
      return Estimator::oadev;
    case Estimator::mtotdev:
    case Estimator::ttotdev:
      return Estimator::mdev;
    case Estimator::htotdev:
      return Estimator::ohdev;
    case Estimator::mtie:
    case Estimator::tierms:
      return std::nullopt;
    default:
      return estimator;
  }
}

bool alpha_in_domain(Estimator estimator, int alpha) {
  const auto proxy = finite_difference_proxy(estimator);
  if (!proxy) return false;
  if (requires_even_factor(estimator) && (alpha < -2 || alpha > 2)) return false;
  const auto v = difference_variance(*proxy);
  if (!v) return false;
  return alpha >= kMinNoiseAlpha && alpha <= kMaxNoiseAlpha && alpha + 2 * v->d > 1;
}

double greenhall_riley_edf_simple(int alpha, const DifferenceVariance& variance, std::size_t m,
                                  std::size_t n_phase) {
  const Setup s = setup(alpha, variance, m, n_phase);
  if (!s.valid) return kNaN;
  const double z0 = sz(0.0, s.F, alpha, variance.d);
  return s.M * z0 * z0 / basic_sum(s.J, s.M, s.S, s.F, alpha, variance.d);
}

double greenhall_riley_edf(int alpha, const DifferenceVariance& variance, std::size_t m,
                           std::size_t n_phase) {
  const Setup s = setup(alpha, variance, m, n_phase);
  if (!s.valid) return kNaN;
  const int d = variance.d;
  const double jmax = static_cast<double>(kJmax);
  const double dd = static_cast<double>(d);
  double inverse = kNaN;

  if (s.F == 1.0) {
    // Case 1: modified variances (and unmodified ones at m = 1), every alpha.
    if (s.J <= jmax) {
      const double z0 = sz(0.0, 1.0, alpha, d);
      inverse = basic_sum(s.J, s.M, s.S, 1.0, alpha, d) / (s.M * z0 * z0);
    } else if (s.r >= dd + 1.0) {
      const TableEntry t = table_entry(kTable1, alpha, d);
      inverse = (t.a0 - t.a1 / s.r) / s.r;
    } else {
      const double m_prime = jmax / s.r;
      const double z0 = sz(0.0, 1.0, alpha, d);
      inverse = basic_sum(jmax, jmax, m_prime, 1.0, alpha, d) / (jmax * z0 * z0);
    }
  } else if (alpha <= 0) {
    // Case 2: unmodified variances, white FM to random-run FM.
    if (s.J <= jmax) {
      const double F = s.m * (dd + 1.0) <= jmax ? s.m : kInf;
      const double z0 = sz(0.0, F, alpha, d);
      inverse = basic_sum(s.J, s.M, s.S, F, alpha, d) / (s.M * z0 * z0);
    } else if (s.r >= dd + 1.0) {
      const TableEntry t = table_entry(kTable2, alpha, d);
      inverse = (t.a0 - t.a1 / s.r) / s.r;
    } else {
      const double m_prime = jmax / s.r;
      const double z0 = sz(0.0, kInf, alpha, d);
      inverse = basic_sum(jmax, jmax, m_prime, kInf, alpha, d) / (jmax * z0 * z0);
    }
  } else if (alpha == 1) {
    // Case 3: unmodified variances, flicker PM; sz(0) grows like ln m.
    const TableEntry b = kTable3[static_cast<std::size_t>(d - 1)];
    const double log_norm = b.a0 + b.a1 * std::log(s.m);
    if (s.J <= jmax) {
      const double z0 = sz(0.0, s.m, alpha, d);
      inverse = basic_sum(s.J, s.M, s.S, s.m, alpha, d) / (s.M * z0 * z0);
    } else if (s.r >= dd + 1.0) {
      const TableEntry t = table_entry(kTable2, alpha, d);
      inverse = (t.a0 - t.a1 / s.r) / (s.r * log_norm * log_norm);
    } else {
      const double m_prime = jmax / s.r;
      inverse = basic_sum(jmax, jmax, m_prime, m_prime, alpha, d) / (jmax * log_norm * log_norm);
    }
  } else {
    // Case 4: unmodified variances, white PM: phase samples are independent, so z_n and z_n'
    // correlate only at lags of k = 1..d multiples of tau, with rho(k) = C(2d, d-k) / C(2d, d).
    const double K = std::ceil(s.r);
    const double c_d = binomial(2 * d, d);
    if (K <= dd) {
      double sum = 0.0;
      for (int k = 1; k < static_cast<int>(K); ++k) {
        const double c = binomial(2 * d, d - k);
        sum += (1.0 - k / s.r) * c * c;
      }
      inverse = (1.0 + 2.0 * sum / (c_d * c_d)) / s.M;
    } else {
      const double a0 = binomial(4 * d, 2 * d) / (c_d * c_d);
      const double a1 = dd / 2.0;
      inverse = (a0 - a1 / s.r) / s.M;
    }
  }
  if (!(inverse > 0.0) || !std::isfinite(inverse)) return kNaN;
  return 1.0 / inverse;
}

double ieee952_edf(std::size_t m, std::size_t n_phase) {
  if (m == 0) return kNaN;
  const double edf = static_cast<double>(n_phase) / static_cast<double>(m) - 1.0;
  return edf > 0.0 ? edf : kNaN;
}

Edf edf(Estimator estimator, int alpha, std::size_t m, std::size_t n_phase) {
  if (const auto variance = difference_variance(estimator)) {
    if (!alpha_in_domain(estimator, alpha)) return {};
    const double value = greenhall_riley_edf(alpha, *variance, m, n_phase);
    if (std::isnan(value)) return {};
    return {value, EdfMethod::greenhall_riley};
  }
  // The total family and Theo1: SP 1065; mtie and tierms: no chi-squared EDF is defined.
  return total_edf(estimator, alpha, m, n_phase);
}

Edf total_edf(Estimator estimator, int alpha, std::size_t m, std::size_t n_phase) {
  if (!alpha_in_domain(estimator, alpha) || m == 0 || n_phase == 0 ||
      m > max_averaging_factor(estimator, n_phase)) {
    return {};
  }
  const double N = static_cast<double>(n_phase);
  const double mm = static_cast<double>(m);
  const double ratio = N / mm;  // T / tau
  auto checked = [](double value, EdfMethod method) -> Edf {
    if (!(value > 0.0) || !std::isfinite(value)) return {};
    return {value, method};
  };
  auto proxy_edf = [&](Estimator proxy) -> Edf {
    const double value = greenhall_riley_edf(alpha, *difference_variance(proxy), m, n_phase);
    return checked(value, EdfMethod::greenhall_riley);
  };
  switch (estimator) {
    case Estimator::totdev: {
      // SP 1065 Table 7, rows alpha = 0, -1, -2.
      constexpr std::array<TableEntry, 3> kTotvar{{{1.50, 0.0}, {1.17, 0.22}, {0.93, 0.36}}};
      if (alpha > 0) return proxy_edf(Estimator::oadev);
      const TableEntry t = kTotvar[static_cast<std::size_t>(-alpha)];
      return checked(t.a0 * ratio - t.a1, EdfMethod::sp1065);
    }
    case Estimator::mtotdev:
    case Estimator::ttotdev: {
      // SP 1065 Table 8, rows alpha = 2 .. -2.
      constexpr std::array<TableEntry, 5> kModTotvar{
          {{1.90, 2.10}, {1.20, 1.40}, {1.10, 1.20}, {0.85, 0.50}, {0.75, 0.31}}};
      const TableEntry t = kModTotvar[static_cast<std::size_t>(2 - alpha)];
      return checked(t.a0 * ratio - t.a1, EdfMethod::sp1065);
    }
    case Estimator::htotdev: {
      constexpr std::array<TableEntry, 3> kHtotvar{{{0.559, 1.004}, {0.868, 1.140}, {0.938, 1.696}}};
      if (m < 16 || alpha > 0 || alpha < -2) return proxy_edf(Estimator::ohdev);
      const TableEntry t = kHtotvar[static_cast<std::size_t>(-alpha)];
      return checked(ratio / (t.a0 + t.a1 / ratio), EdfMethod::sp1065);
    }
    case Estimator::theo1:
    case Estimator::theobr: {  // ThêoBR is theo1 times a constant: the same EDF
      const double r = 0.75 * mm;
      double value = kNaN;
      switch (alpha) {
        case 2:
          value = 0.86 * (N + 1.0) * (N - 4.0 * r / 3.0) / (N - r) * r / (r + 1.14);
          break;
        case 1:
          value = (4.798 * N * N - 6.374 * N * r + 12.387 * r) / (std::sqrt(r + 36.6) * (N - r)) *
                  r / (r + 0.3);
          break;
        case 0: {
          const double r15 = r * std::sqrt(r);
          value = ((4.1 * N + 0.8) / r - (3.1 * N + 6.5) / N) * r15 / (r15 + 5.2);
          break;
        }
        case -1: {
          const double r3 = r * r * r;
          value = (2.0 * N * N - 1.3 * N * r - 3.5 * r) / (N * r) * r3 / (r3 + 2.3);
          break;
        }
        case -2: {
          const double a = 4.4 * N - 1.0;
          const double b = 4.4 * N - 3.0;
          value = (4.4 * N - 2.0) / (2.9 * r) * (a * a - 8.6 * r * a + 11.4 * r * r) / (b * b);
          break;
        }
        default:
          break;
      }
      return checked(value, EdfMethod::sp1065);
    }
    default:
      return {};
  }
}

}  // namespace imunoise
