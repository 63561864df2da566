#include "imunoise/nav/schuler.hpp"

#include <cmath>
#include <complex>

namespace imunoise::nav::schuler {
namespace {

// Below this w0 t the closed forms lose more than ~1e-12 to cancellation: use power series.
constexpr double kSeriesBelow = 1.0;
constexpr int kSeriesTerms = 14;  // x < 1: the next term is below 1e-30 relative

// x - sin x = sum_{k>=1} (-1)^(k+1) x^(2k+1) / (2k+1)!
double x_minus_sin(double x) {
  if (std::abs(x) >= kSeriesBelow) return x - std::sin(x);
  double term = x * x * x / 6.0, sum = 0.0;
  for (int k = 1; k <= kSeriesTerms; ++k) {
    sum += term;
    term *= -x * x / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
  }
  return sum;
}

// x^2/2 - (1 - cos x) = sum_{k>=2} (-1)^k x^(2k) / (2k)!
double half_x2_minus_one_minus_cos(double x) {
  if (std::abs(x) >= kSeriesBelow) return 0.5 * x * x - (1.0 - std::cos(x));
  double term = x * x * x * x / 24.0, sum = 0.0;
  for (int k = 2; k <= kSeriesTerms; ++k) {
    sum += term;
    term *= -x * x / ((2.0 * k + 1.0) * (2.0 * k + 2.0));
  }
  return sum;
}

// int_0^x (1 - cos y)^2 dy = 1.5 x - 2 sin x + sin(2x)/4; series from the product of
// 1 - cos y = sum_{k>=1} b_k y^(2k), b_k = (-1)^(k+1)/(2k)!.
double integral_one_minus_cos_squared(double x) {
  if (x >= kSeriesBelow) return 1.5 * x - 2.0 * std::sin(x) + 0.25 * std::sin(2.0 * x);
  double b[kSeriesTerms + 1];
  double f = 1.0;  // (2k)!
  for (int k = 1; k <= kSeriesTerms; ++k) {
    f *= (2.0 * k - 1.0) * (2.0 * k);
    b[k] = ((k % 2) ? 1.0 : -1.0) / f;
  }
  double sum = 0.0;
  for (int j = kSeriesTerms; j >= 1; --j) {
    for (int k = kSeriesTerms; k >= 1; --k) {
      const int p = 2 * j + 2 * k + 1;
      sum += b[j] * b[k] * std::pow(x, p) / p;
    }
  }
  return sum;
}

// int_0^x (y - sin y)^2 dy = x^3/3 - 2 (sin x - x cos x) + x/2 - sin(2x)/4; series from
// y - sin y = sum_{k>=1} a_k y^(2k+1), a_k = (-1)^(k+1)/(2k+1)!.
double integral_x_minus_sin_squared(double x) {
  if (x >= kSeriesBelow) {
    return x * x * x / 3.0 - 2.0 * (std::sin(x) - x * std::cos(x)) + 0.5 * x - 0.25 * std::sin(2.0 * x);
  }
  double a[kSeriesTerms + 1];
  double f = 1.0;  // (2k+1)!
  for (int k = 1; k <= kSeriesTerms; ++k) {
    f *= (2.0 * k) * (2.0 * k + 1.0);
    a[k] = ((k % 2) ? 1.0 : -1.0) / f;
  }
  double sum = 0.0;
  for (int j = kSeriesTerms; j >= 1; --j) {
    for (int k = kSeriesTerms; k >= 1; --k) {
      const int p = 2 * j + 2 * k + 3;
      sum += a[j] * a[k] * std::pow(x, p) / p;
    }
  }
  return sum;
}

using cplx = std::complex<double>;

// E(z) = int_0^t e^{z a} da = (e^{z t} - 1) / z, with its limit t at z = 0.
cplx integral_exp(cplx z, double t) {
  const cplx zt = z * t;
  if (std::abs(zt) < 1e-5) return t * (1.0 + zt / 2.0 + zt * zt / 6.0);
  return (std::exp(zt) - 1.0) / z;
}

// I(l, m) = int_0^t int_0^t e^{l a} e^{m b} e^{-|a-b|/T} db da, c = 1/T, m != +-c.
cplx double_integral(cplx l, cplx m, double c, double t) {
  const cplx e_lm = integral_exp(l + m, t);
  const cplx first = (e_lm - integral_exp(l - c, t)) / (m + c);
  const cplx second = ((std::exp((l + m) * t) - std::exp((m - c) * t)) / (l + c) - e_lm) / (m - c);
  return first + second;
}

// 1 - cos x, without cancellation for small x: 2 sin^2(x/2).
double one_minus_cos(double x) {
  const double s = std::sin(0.5 * x);
  return 2.0 * s * s;
}

// int_0^x sin^2 y dy = x/2 - sin(2x)/4, by its series below 1 (it grows like x^3/3).
double integral_sin_squared(double x) {
  if (std::abs(x) >= kSeriesBelow) return 0.5 * x - 0.25 * std::sin(2.0 * x);
  // x/2 - sin(2x)/4 = sum_{k>=1} (-1)^(k+1) (2x)^(2k+1) / (4 (2k+1)!)
  const double y = 2.0 * x;
  double term = y * y * y / 6.0, sum = 0.0;
  for (int k = 1; k <= kSeriesTerms; ++k) {
    sum += term;
    term *= -y * y / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
  }
  return 0.25 * sum;
}

// sigma^2 int int h(a) h(b) e^{-|a-b|/T} da db for h(u) = sum_j coef_j e^{lambda_j u}.
double exponential_sum_variance(const cplx* lambda, const cplx* coef, int n, double sigma, double time_s, double t_s) {
  const double c = 1.0 / time_s;
  cplx sum = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n; ++k) sum += coef[j] * coef[k] * double_integral(lambda[j], lambda[k], c, t_s);
  }
  return sigma * sigma * sum.real();
}

}  // namespace

double frequency_rad_s(double gravity_m_s2, double radius_m) { return std::sqrt(gravity_m_s2 / radius_m); }

double constant_drift_rad(double bias_rad_s, double t_s, double w0) {
  return std::abs(bias_rad_s) * x_minus_sin(w0 * t_s) / w0;
}

double constant_drift_tilt_rad(double bias_rad_s, double t_s, double w0) {
  return std::abs(bias_rad_s * std::sin(w0 * t_s) / w0);
}

double rate_ramp_rad(double ramp_rad_s2, double t_s, double w0) {
  return std::abs(ramp_rad_s2) * half_x2_minus_one_minus_cos(w0 * t_s) / (w0 * w0);
}

double white_rad(double n, double t_s, double w0) {
  return n * std::sqrt(integral_one_minus_cos_squared(w0 * t_s) / w0);
}

double random_walk_rad(double k, double t_s, double w0) {
  return k * std::sqrt(integral_x_minus_sin_squared(w0 * t_s) / (w0 * w0 * w0));
}

double gauss_markov_rad(double sigma, double time_s, double t_s, double w0) {
  if (sigma == 0.0 || t_s <= 0.0) return 0.0;
  // h(u) = -1 + e^{i w0 u}/2 + e^{-i w0 u}/2
  const cplx lambda[3] = {cplx(0.0, 0.0), cplx(0.0, w0), cplx(0.0, -w0)};
  const cplx coef[3] = {-1.0, 0.5, 0.5};
  const double var = exponential_sum_variance(lambda, coef, 3, sigma, time_s, t_s);
  return var > 0.0 ? std::sqrt(var) : 0.0;
}

double quantization_rad(double q, double h, double t_s, double w0) {
  if (q == 0.0) return 0.0;
  const long k = std::lround(t_s / h);
  if (k <= 0) return 0.0;
  const double xh = w0 * h;
  // A_m = int_{(m-1)h}^{mh} (1 - cos w0 u) du = (s(w0 m h) - s(w0 (m-1) h)) / w0, s(x) = x - sin x
  const double a1 = x_minus_sin(xh) / w0;
  const double ak = (x_minus_sin(xh * static_cast<double>(k)) - x_minus_sin(xh * static_cast<double>(k - 1))) / w0;
  const double s_half = std::sin(0.5 * xh);
  const double gain = 4.0 * s_half * s_half / w0;
  // sum_{m=1}^{k-1} sin^2(m xh) = (k-1)/2 - sin((k-1) xh) cos(k xh) / (2 sin xh); the closed
  // form cancels while k xh is small (the sum ~ xh^2 k^3 / 3), where the direct sum is short.
  double sum = 0.0;
  const double kd = static_cast<double>(k);
  if (kd * xh < 0.5) {
    for (long m = 1; m < k; ++m) {
      const double s = std::sin(xh * static_cast<double>(m));
      sum += s * s;
    }
  } else {
    sum = 0.5 * (kd - 1.0) - std::sin((kd - 1.0) * xh) * std::cos(kd * xh) / (2.0 * std::sin(xh));
  }
  const double var = (q / h) * (q / h) * (a1 * a1 + ak * ak + gain * gain * sum);
  return std::sqrt(var);
}

double accel_bias_rad(double bias, double t_s, double w0, double radius_m) {
  return std::abs(bias) * one_minus_cos(w0 * t_s) / (radius_m * w0 * w0);
}

double accel_ramp_rad(double ramp, double t_s, double w0, double radius_m) {
  return std::abs(ramp) * x_minus_sin(w0 * t_s) / (radius_m * w0 * w0 * w0);
}

double accel_white_rad(double n, double t_s, double w0, double radius_m) {
  return n / (radius_m * w0) * std::sqrt(integral_sin_squared(w0 * t_s) / w0);
}

double accel_random_walk_rad(double k, double t_s, double w0, double radius_m) {
  return white_rad(k / (radius_m * w0 * w0), t_s, w0);
}

double accel_gauss_markov_rad(double sigma, double time_s, double t_s, double w0, double radius_m) {
  if (sigma == 0.0 || t_s <= 0.0) return 0.0;
  // h_f(u) = (e^{i w0 u} - e^{-i w0 u}) / (2 i R w0)
  const cplx lambda[2] = {cplx(0.0, w0), cplx(0.0, -w0)};
  const cplx unit = 1.0 / (cplx(0.0, 2.0) * radius_m * w0);
  const cplx coef[2] = {unit, -unit};
  const double var = exponential_sum_variance(lambda, coef, 2, sigma, time_s, t_s);
  return var > 0.0 ? std::sqrt(var) : 0.0;
}

double accel_quantization_rad(double q, double h, double t_s, double w0, double radius_m) {
  if (q == 0.0) return 0.0;
  const long k = std::lround(t_s / h);
  if (k <= 0) return 0.0;
  const double xh = w0 * h;
  const double g = radius_m * w0 * w0;
  // B_m = int_{(m-1)h}^{mh} h_f(u) du = (cos(w0 (m-1) h) - cos(w0 m h)) / g; the response at
  // t = k h is (1/h) [q_k B_1 - q_0 B_k + sum_{i=1}^{k-1} q_i (B_{k-i+1} - B_{k-i})].
  const double kd = static_cast<double>(k);
  const double b1 = one_minus_cos(xh) / g;
  const double bk = 2.0 * std::sin(xh * (kd - 0.5)) * std::sin(0.5 * xh) / g;
  const double s_half = std::sin(0.5 * xh);
  const double gain = 4.0 * s_half * s_half / g;  // B_{m+1} - B_m = gain cos(m xh)
  // sum_{m=1}^{k-1} cos^2(m xh) = (k-1)/2 + sin((k-1) xh) cos(k xh) / (2 sin xh): both parts
  // grow like k, so the closed form does not cancel (the direct sum only where sin xh = 0).
  double sum = 0.0;
  if (std::abs(std::sin(xh)) > 1e-12) {
    sum = 0.5 * (kd - 1.0) + std::sin((kd - 1.0) * xh) * std::cos(kd * xh) / (2.0 * std::sin(xh));
  } else {
    for (long m = 1; m < k; ++m) {
      const double c = std::cos(xh * static_cast<double>(m));
      sum += c * c;
    }
  }
  const double var = (q / h) * (q / h) * (b1 * b1 + bk * bk + gain * gain * sum);
  return std::sqrt(var);
}

}  // namespace imunoise::nav::schuler
