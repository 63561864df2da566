#include "deterministic_fp.hpp"  // first: no fused multiply-add in this file

#include "imunoise/sim/portable_math.hpp"

#include <cmath>
#include <limits>

namespace imunoise::sim::portable {
namespace {

// ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (its low 21 bits are zero).
constexpr double kLn2Hi = 0x1.62e42fee00000p-1;
constexpr double kLn2Lo = 0x1.a39ef35793c76p-33;
constexpr double kInvLn2 = 0x1.71547652b82fep0;
constexpr double kTwoPi = 0x1.921fb54442d18p2;

// n! for n = 0..22, all exact in double.
constexpr double kFactorial[23] = {
    1.0,
    1.0,
    2.0,
    6.0,
    24.0,
    120.0,
    720.0,
    5040.0,
    40320.0,
    362880.0,
    3628800.0,
    39916800.0,
    479001600.0,
    6227020800.0,
    87178291200.0,
    1307674368000.0,
    20922789888000.0,
    355687428096000.0,
    6402373705728000.0,
    121645100408832000.0,
    2432902008176640000.0,
    51090942171709440000.0,
    1124000727777607680000.0};

// e^r - 1 for |r| < 1 by its Taylor series to r^22 (truncation < 1e-21), Horner.
double expm1_series(double r) {
  double p = 1.0 / kFactorial[22];
  for (int n = 21; n >= 3; --n) p = 1.0 / kFactorial[n] + r * p;
  p = 0.5 + r * p;
  return r + (r * r) * p;
}

}  // namespace

double exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (x < -745.2) return 0.0;
  const double k = std::nearbyint(x * kInvLn2);  // |k| <= 1076
  const double r = (x - k * kLn2Hi) - k * kLn2Lo; // |r| <= 0.3466 (+ rounding)
  const double e = 1.0 + expm1_series(r);
  // Scale in two exact steps so that 2^k never overflows before the product underflows.
  const int ki = static_cast<int>(k);
  const int half = ki / 2;
  return std::ldexp(std::ldexp(e, half), ki - half);
}

double expm1(double x) {
  if (std::isnan(x)) return x;
  if (std::fabs(x) < 1.0) return expm1_series(x);
  if (x < -40.0) return -1.0;
  return exp(x) - 1.0;  // |e^x - 1| >= 0.63 here: no cancellation
}

double log(double x) {
  if (!(x > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(x)) return x;
  int e = 0;
  double m = std::frexp(x, &e);  // x = m * 2^e, m in [0.5, 1); exact (also for subnormals)
  if (m < 0x1.6a09e667f3bcdp-1) {  // 1/sqrt(2)
    m *= 2.0;
    --e;
  }
  // m in [0.7071, 1.4142): log m = 2 atanh(s), s = (m - 1)/(m + 1), |s| <= 0.1716.
  const double f = m - 1.0;  // exact (Sterbenz)
  const double s = f / (2.0 + f);
  const double s2 = s * s;  // <= 0.02944; series to s^25 leaves < 2e-20 relative
  double p = 1.0 / 25.0;
  p = 1.0 / 23.0 + s2 * p;
  p = 1.0 / 21.0 + s2 * p;
  p = 1.0 / 19.0 + s2 * p;
  p = 1.0 / 17.0 + s2 * p;
  p = 1.0 / 15.0 + s2 * p;
  p = 1.0 / 13.0 + s2 * p;
  p = 1.0 / 11.0 + s2 * p;
  p = 1.0 / 9.0 + s2 * p;
  p = 1.0 / 7.0 + s2 * p;
  p = 1.0 / 5.0 + s2 * p;
  p = 1.0 / 3.0 + s2 * p;
  // log m = 2s (1 + s^2/3 + s^4/5 + ...) = 2s + 2s s^2 p.
  const double log_m = 2.0 * s + 2.0 * s * (s2 * p);
  const double de = static_cast<double>(e);
  return de * kLn2Hi + (de * kLn2Lo + log_m);
}

std::pair<double, double> sincos_cycles(double cycles) {
  if (!std::isfinite(cycles)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan};
  }
  const double t = cycles - std::nearbyint(cycles);  // exact, in [-0.5, 0.5]
  const double q = std::nearbyint(4.0 * t);          // quadrant, -2..2
  const double u = t - 0.25 * q;                     // exact, in [-1/8, 1/8] turn
  const double a = kTwoPi * u;                       // |a| <= pi/4
  const double a2 = a * a;
  // sin a = a (1 - a^2/3! + ... - a^18/19!), cos a = 1 - a^2/2! + ... + a^18/18!;
  // truncation below 1e-19 for |a| <= pi/4.
  double ps = -1.0 / 121645100408832000.0;  // -1/19!
  ps = 1.0 / 355687428096000.0 + a2 * ps;   // 1/17!
  ps = -1.0 / 1307674368000.0 + a2 * ps;    // -1/15!
  ps = 1.0 / 6227020800.0 + a2 * ps;        // 1/13!
  ps = -1.0 / 39916800.0 + a2 * ps;         // -1/11!
  ps = 1.0 / 362880.0 + a2 * ps;            // 1/9!
  ps = -1.0 / 5040.0 + a2 * ps;             // -1/7!
  ps = 1.0 / 120.0 + a2 * ps;               // 1/5!
  ps = -1.0 / 6.0 + a2 * ps;                // -1/3!
  const double s = a + a * (a2 * ps);
  double pc = 1.0 / 6402373705728000.0;     // 1/18!
  pc = -1.0 / 20922789888000.0 + a2 * pc;   // -1/16!
  pc = 1.0 / 87178291200.0 + a2 * pc;       // 1/14!
  pc = -1.0 / 479001600.0 + a2 * pc;        // -1/12!
  pc = 1.0 / 3628800.0 + a2 * pc;           // 1/10!
  pc = -1.0 / 40320.0 + a2 * pc;            // -1/8!
  pc = 1.0 / 720.0 + a2 * pc;               // 1/6!
  pc = -1.0 / 24.0 + a2 * pc;               // -1/4!
  pc = 0.5 + a2 * pc;                       // cos a = 1 - a^2 (1/2! - a^2/4! + ...)
  const double c = 1.0 - a2 * pc;
  switch (static_cast<int>(q)) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case -1: return {-c, s};
    default: return {-s, -c};  // +-2: half a turn
  }
}

}  // namespace imunoise::sim::portable
