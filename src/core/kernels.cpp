#include "kernels.hpp"

#include <algorithm>
#include <utility>
#include <vector>

// GCC builds AVX-512, AVX2+FMA and baseline clones, picked by the loader (ifunc).
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define IMUNOISE_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define IMUNOISE_CLONES
#endif

// The 64-byte vector type only crosses always-inline helpers, never a real call boundary, so
// GCC's note that its ABI would differ without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace imunoise::detail {
namespace {

// Four independent accumulators of eight lanes: a single accumulator would serialise on the
// latency of the add. Eight lanes are one AVX-512 register, two AVX2 ones, four SSE2 ones:
// each clone gets the widest operations it has.
typedef double Vec8 __attribute__((vector_size(64)));
constexpr std::size_t kLanes = 8;
static_assert(sizeof(Vec8) == kLanes * sizeof(double));
constexpr std::size_t kUnroll = 4;

__attribute__((always_inline)) inline Vec8 load(const double* p) {
  Vec8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

__attribute__((always_inline)) inline double horizontal_sum(const Vec8 (&acc)[kUnroll]) {
  const Vec8 s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

// Sum of squares of a finite difference of order 2 or 3. No lambdas or non-inlined helpers:
// in a target_clones function every callee must be inlined, or a 64-byte vector would cross a
// call between code built for different instruction sets (it does at -O0 otherwise).
template <int Order>
__attribute__((always_inline)) inline double sum_sq_difference(const double* x, std::size_t m,
                                                                std::size_t count) {
  const double* x0 = x;
  const double* x1 = x + m;
  const double* x2 = x + 2 * m;
  const double* x3 = x + 3 * m;
  Vec8 acc[kUnroll] = {};
  std::size_t k = 0;
  for (; k + kLanes * kUnroll <= count; k += kLanes * kUnroll) {
    for (std::size_t u = 0; u < kUnroll; ++u) {
      const std::size_t i = k + u * kLanes;
      Vec8 d;
      if constexpr (Order == 2) {
        d = load(x2 + i) - 2.0 * load(x1 + i) + load(x0 + i);
      } else {
        d = load(x3 + i) - 3.0 * load(x2 + i) + 3.0 * load(x1 + i) - load(x0 + i);
      }
      acc[u] += d * d;
    }
  }
  double sum = horizontal_sum(acc);
  for (; k < count; ++k) {
    double d;
    if constexpr (Order == 2) {
      d = x2[k] - 2.0 * x1[k] + x0[k];
    } else {
      d = x3[k] - 3.0 * x2[k] + 3.0 * x1[k] - x0[k];
    }
    sum += d * d;
  }
  return sum;
}

}  // namespace

IMUNOISE_CLONES double sum_sq_second_difference(const double* x, std::size_t m,
                                                std::size_t count) {
  return sum_sq_difference<2>(x, m, count);
}

IMUNOISE_CLONES double sum_sq_third_difference(const double* x, std::size_t m,
                                               std::size_t count) {
  return sum_sq_difference<3>(x, m, count);
}

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
namespace {

// Eight samples starting Off elements into the window w (consecutive loaded vectors).
template <int Off, int Count>
__attribute__((always_inline, target("avx512f,fma"))) inline Vec8 shifted(const Vec8 (&w)[Count]) {
  constexpr int q = Off / 8;
  constexpr int r = Off % 8;
  if constexpr (r == 0) {
    return w[q];
  } else {
    return __builtin_shufflevector(w[q], w[q + 1], r, r + 1, r + 2, r + 3, r + 4, r + 5, r + 6, r + 7);
  }
}

template <int Count>
__attribute__((always_inline, target("avx512f,fma"))) inline void load_window(const double* p, Vec8 (&w)[Count]) {
  for (int q = 0; q < Count; ++q) w[q] = load(p + 8 * q);
}

// How a second difference's terms are formed; the best depends on the core's execution ports.
// separate_adders: b shuffled out of the loaded window and the first three factors as
// (c - b) - (b - a), which runs on the adders while the other five keep the multiply-add units
// busy: 21 % faster on Zen 5 (separate add and multiply-add pipes, an idle shuffle unit) than
// one form for all (bench_deviation oadev_all; docs/performance.md). shared_ports: b and c by
// unaligned loads and every factor as c - 2b + a, for cores whose adds, multiply-adds and
// shuffles share two vector ports (Intel): 27 % faster than separate_adders on a Xeon 6.207
// (2026-12-06), where that form is bound by its 34 port operations per 64 terms.
enum class Form { separate_adders, shared_ports };

// The term of factor m + J at the eight starts of the step, from the windows of each stream;
// the far sample c by an unaligned load (the load ports have room on every core measured).
template <int Order, Form F, int J>
__attribute__((always_inline, target("avx512f,fma"))) inline Vec8 run_term(const Vec8& a, const Vec8 (&w1)[2],
                                                                           const double* x1, const double* x2,
                                                                           const Vec8 (&w2)[3], const double* x3) {
  if constexpr (Order == 2) {
    const Vec8 c = load(x2 + 2 * J);
    if constexpr (F == Form::shared_ports) {
      return c - 2.0 * load(x1 + J) + a;
    } else {
      const Vec8 b = shifted<J>(w1);
      if constexpr (J < 3) {
        return (c - b) - (b - a);
      } else {
        return c - 2.0 * b + a;
      }
    }
  } else {
    // Third differences as (d - a) - 3 (c - b): two adds and one multiply-add, balanced
    // between the units, where the textbook form needs three multiply-adds; d loaded directly.
    const Vec8 d = load(x3 + 3 * J);
    return (d - a) - 3.0 * (shifted<2 * J>(w2) - shifted<J>(w1));
  }
}

template <int Order, Form F, int J>
__attribute__((always_inline, target("avx512f,fma"))) inline void add_term(Vec8& acc, const Vec8& a, const Vec8 (&w1)[2],
                                                                           const double* x1, const double* x2,
                                                                           const Vec8 (&w2)[3], const double* x3) {
  const Vec8 d = run_term<Order, F, J>(a, w1, x1, x2, w2, x3);
  acc += d * d;
}

template <int Order, Form F, std::size_t... J>
__attribute__((always_inline, target("avx512f,fma"))) inline void run_sums(const double* x, std::size_t m,
                                                                           std::size_t count, std::size_t readable,
                                                                           double* sums,
                                                                           std::index_sequence<J...>) {
  Vec8 acc[8] = {};
  Vec8 w1[2], w2[3];
  // The last stream's whole vectors reach 2 (Order 2) or 3 (Order 3) samples past the last one
  // the eighth factor's term needs, which may be the record's last: those starts go scalar.
  constexpr std::size_t kSlack = Order == 2 ? 2 : 3;
  std::size_t k = 0;
  const std::size_t vector_end = std::min(count, readable >= kSlack ? readable - kSlack : 0);
  for (; k + kLanes <= vector_end; k += kLanes) {
    const Vec8 a = load(x + k);
    if constexpr (Order == 3 || F == Form::separate_adders) load_window(x + k + m, w1);
    if constexpr (Order == 3) load_window(x + k + 2 * m, w2);
    (add_term<Order, F, static_cast<int>(J)>(acc[J], a, w1, x + k + m, x + k + 2 * m, w2, x + k + 3 * m), ...);
  }
  for (std::size_t j = 0; j < 8; ++j) {
    const Vec8& s = acc[j];
    double sum = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
    // The last few starts (fewer than 8 + kSlack) by the one-factor kernel's own loop.
    sums[j] = sum + sum_sq_difference<Order>(x + k, m + j, count - k);
  }
}

/// The form for this machine's cores, chosen once: the vendor decides the port layout (both
/// forms round differently, by ~1e-16 of a term, so one machine always uses the same one).
bool shared_ports() {
  static const bool intel = __builtin_cpu_is("intel");
  return intel;
}

}  // namespace

__attribute__((target("avx512f,fma"))) void sum_sq_second_difference_run8(const double* x, std::size_t m,
                                                                          std::size_t count, std::size_t readable,
                                                                          double* sums) {
  if (shared_ports()) {
    run_sums<2, Form::shared_ports>(x, m, count, readable, sums, std::make_index_sequence<8>{});
  } else {
    run_sums<2, Form::separate_adders>(x, m, count, readable, sums, std::make_index_sequence<8>{});
  }
}

__attribute__((target("avx512f,fma"))) void sum_sq_third_difference_run8(const double* x, std::size_t m,
                                                                         std::size_t count, std::size_t readable,
                                                                         double* sums) {
  run_sums<3, Form::separate_adders>(x, m, count, readable, sums, std::make_index_sequence<8>{});
}

bool difference_runs_available() {
  static const bool available = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("fma");
  return available;
}
#else
bool difference_runs_available() { return false; }
void sum_sq_second_difference_run8(const double*, std::size_t, std::size_t, std::size_t, double*) {}
void sum_sq_third_difference_run8(const double*, std::size_t, std::size_t, std::size_t, double*) {}
#endif

namespace {

// In-vector inclusive prefix sum of eight lanes (lane i: sum of lanes 0..i), three shift-adds.
__attribute__((always_inline)) inline Vec8 inclusive_scan(Vec8 v) {
  const Vec8 zero = {};
  v += __builtin_shufflevector(v, zero, 8, 0, 1, 2, 3, 4, 5, 6);
  v += __builtin_shufflevector(v, zero, 8, 8, 0, 1, 2, 3, 4, 5);
  v += __builtin_shufflevector(v, zero, 8, 8, 8, 8, 0, 1, 2, 3);
  return v;
}

__attribute__((always_inline)) inline Vec8 broadcast_last(Vec8 v) {
  return __builtin_shufflevector(v, v, 7, 7, 7, 7, 7, 7, 7, 7);
}

}  // namespace

IMUNOISE_CLONES void compensated_prefix(const double* rate, std::size_t n, double offset,
                                        double tau0_s, double& sum_io, double& compensation_io,
                                        double* out) {
  double sum = sum_io;
  double compensation = compensation_io;
  const Vec8 offsets = Vec8{} + offset;
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    const Vec8 p = inclusive_scan(load(rate + i) - offsets);
    const Vec8 carry = Vec8{} + sum;
    const Vec8 total = carry + p;  // two-sum: total + error == carry + p exactly
    const Vec8 p_part = total - carry;
    const Vec8 error = (carry - (total - p_part)) + (p - p_part);
    const Vec8 x = (total + (compensation + error)) * tau0_s;
    __builtin_memcpy(out + i, &x, sizeof x);
    sum = total[kLanes - 1];
    compensation += error[kLanes - 1];
  }
  for (; i < n; ++i) {
    neumaier_add(sum, compensation, rate[i] - offset);
    out[i] = (sum + compensation) * tau0_s;
  }
  sum_io = sum;
  compensation_io = compensation;
}

IMUNOISE_CLONES double sum_sq_window_second_difference(const double* x, std::size_t m,
                                                       std::size_t count, double* second_sum) {
  const double* x0 = x;
  const double* x1 = x + m;
  const double* x2 = x + 2 * m;
  const double* x3 = x + 3 * m;
  // v_0, eight lanes then a fixed-order reduction.
  Vec8 lanes = {};
  std::size_t i = 0;
  for (; i + kLanes <= m; i += kLanes) lanes += (load(x2 + i) - 2.0 * load(x1 + i)) + load(x0 + i);
  double v = ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
  for (; i < m; ++i) v += (x2[i] - 2.0 * x1[i]) + x0[i];
  double sum = v * v;
  // Windows 1 .. count-1: v_{k+1} = v_k + inc_k, inc_k = e_{k+m} - e_k, k = 0 .. count-2.
  const std::size_t steps = count - 1;
  Vec8 acc[2] = {};
  Vec8 acc_e[2] = {};
  Vec8 carry = {v, v, v, v, v, v, v, v};
  std::size_t k = 0;
  for (; k + 2 * kLanes <= steps; k += 2 * kLanes) {
    for (std::size_t u = 0; u < 2; ++u) {
      const std::size_t j = k + u * kLanes;
      const Vec8 a1 = load(x1 + j), a2 = load(x2 + j);
      const Vec8 e = (a2 - 2.0 * a1) + load(x0 + j);
      const Vec8 inc = ((load(x3 + j) - 2.0 * a2) + a1) - e;
      const Vec8 prefix = inclusive_scan(inc);
      const Vec8 w = carry + prefix;
      acc[u] += w * w;
      acc_e[u] += e * e;
      carry += broadcast_last(prefix);
    }
  }
  const Vec8 s = acc[0] + acc[1];
  sum += ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
  const Vec8 se = acc_e[0] + acc_e[1];
  double e_sum = ((se[0] + se[1]) + (se[2] + se[3])) + ((se[4] + se[5]) + (se[6] + se[7]));
  v = carry[0];
  for (; k < steps; ++k) {
    const double e = (x2[k] - 2.0 * x1[k]) + x0[k];
    v += ((x3[k] - 2.0 * x2[k]) + x1[k]) - e;
    sum += v * v;
    e_sum += e * e;
  }
  if (second_sum != nullptr) *second_sum = e_sum;
  return sum;
}

namespace {

// Entries [begin, end) of one doubling step: the windows' squares into acc (Sum) and/or d
// replaced by the next octave (Update). Every load of a vector step precedes its store, and the
// store is at the lowest index the step reads: the in-place update never reads an entry it has
// already overwritten, for any m >= 1.
template <bool Sum, bool Update>
__attribute__((always_inline)) inline double doubling_range(double* d, std::size_t m, std::size_t begin,
                                                            std::size_t end) {
  Vec8 acc[2] = {};
  std::size_t k = begin;
  for (; k + 2 * kLanes <= end; k += 2 * kLanes) {
    for (std::size_t u = 0; u < 2; ++u) {
      const std::size_t i = k + u * kLanes;
      const Vec8 d0 = load(d + i), d1 = load(d + i + m);
      if constexpr (Sum) {
        const Vec8 v = d1 - d0;
        acc[u] += v * v;
      }
      if constexpr (Update) {
        const Vec8 doubled = (d0 + load(d + i + 2 * m)) + 2.0 * d1;
        __builtin_memcpy(d + i, &doubled, sizeof doubled);
      }
    }
  }
  const Vec8 s = acc[0] + acc[1];
  double sum = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
  for (; k < end; ++k) {
    if constexpr (Sum) {
      const double v = d[k + m] - d[k];
      sum += v * v;
    }
    if constexpr (Update) d[k] = (d[k] + d[k + 2 * m]) + 2.0 * d[k + m];
  }
  return sum;
}

}  // namespace

IMUNOISE_CLONES double sum_sq_window_doubling_step(double* d, std::size_t m, std::size_t count,
                                                   std::size_t next) {
  const std::size_t both = std::min(count, next);
  double sum = doubling_range<true, true>(d, m, 0, both);
  if (count > both) sum += doubling_range<true, false>(d, m, both, count);
  if (next > both) doubling_range<false, true>(d, m, both, next);
  return sum;
}

IMUNOISE_CLONES double sum_sq_window_doubling_first(const double* x, std::size_t count,
                                                    std::size_t next, double slope, double* d) {
  // m = 1 from x itself: v_k = x[k+2] - 2 x[k+1] + x[k], D_2(k) = (x[k+3] - x[k+1]) + (x[k+2] - x[k]).
  const double shift = 4.0 * slope;
  const std::size_t both = std::min(count, next);
  Vec8 acc[2] = {};
  std::size_t k = 0;
  for (; k + 2 * kLanes <= both; k += 2 * kLanes) {
    for (std::size_t u = 0; u < 2; ++u) {
      const std::size_t i = k + u * kLanes;
      const Vec8 x0 = load(x + i), x1 = load(x + i + 1), x2 = load(x + i + 2);
      const Vec8 v = (x2 - 2.0 * x1) + x0;
      acc[u] += v * v;
      const Vec8 doubled = ((load(x + i + 3) - x1) + (x2 - x0)) - shift;
      __builtin_memcpy(d + i, &doubled, sizeof doubled);
    }
  }
  const Vec8 s = acc[0] + acc[1];
  double sum = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
  for (std::size_t j = k; j < count; ++j) {
    const double v = (x[j + 2] - 2.0 * x[j + 1]) + x[j];
    sum += v * v;
  }
  for (std::size_t j = k; j < next; ++j) d[j] = ((x[j + 3] - x[j + 1]) + (x[j + 2] - x[j])) - shift;
  return sum;
}

IMUNOISE_CLONES double sum_sq_window_tile_rows(const double* tile, std::size_t lag,
                                               const double* v0, std::size_t rows) {
  constexpr std::size_t kWidth = 64;
  // Lane 7 of the last vector is the window at column 64: the next row's start, not this row's.
  const Vec8 last_mask = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0};
  Vec8 acc[2] = {};
  double first = 0.0;
  for (std::size_t r = 0; r < rows; ++r) {
    const double* t0 = tile + r * kWidth;
    const double* t1 = t0 + lag;
    const double* t2 = t0 + 2 * lag;
    const double* t3 = t0 + 3 * lag;
    const double v = v0[r];
    first += v * v;
    Vec8 carry = {v, v, v, v, v, v, v, v};
    for (std::size_t k = 0; k < kWidth; k += kLanes) {
      const Vec8 a1 = load(t1 + k), a2 = load(t2 + k);
      const Vec8 inc = ((load(t3 + k) - 2.0 * a2) + a1) - ((a2 - 2.0 * a1) + load(t0 + k));
      const Vec8 prefix = inclusive_scan(inc);
      Vec8 w = carry + prefix;
      if (k + kLanes == kWidth) w *= last_mask;
      acc[(k / kLanes) & 1] += w * w;
      carry += broadcast_last(prefix);
    }
  }
  const Vec8 s = acc[0] + acc[1];
  return first + (((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7])));
}

namespace {

// The six third differences z_{r+km} (k = 0..5) as combinations of the subsequence prefix P at
// t = 3m-r, 2m-r, m-r, r, r+m, r+2m (in that order), plus gamma_k times 2T, T = P(3m): the prefix
// of the 9m reflected sequence (less a constant) at r + k m, k = 0..8, is -P(3m-r), -P(2m-r),
// -P(m-r), P(r), P(r+m), P(r+2m), 2T-P(3m-r), 2T-P(2m-r), 2T-P(m-r).
constexpr int kZ[6][6] = {{1, -3, 3, 1, 0, 0},  {0, 1, -3, -3, 1, 0}, {0, 0, 1, 3, -3, 1},
                          {-1, 0, 0, -1, 3, -3}, {3, -1, 0, 0, -1, 3}, {-3, 3, -1, 0, 0, -1}};
constexpr int kGamma[6] = {0, 0, 0, 1, -2, 1};

// P(t) = (ul[t] - ul[0]) - mean t - slope t (t - 1) / 2, eight windows at once.
__attribute__((always_inline)) inline Vec8 detrended_prefix(const double* ul, std::size_t t,
                                                           Vec8 base, Vec8 mean, Vec8 slope) {
  const double td = static_cast<double>(t);
  return (load(ul + t) - base) - mean * td - slope * (0.5 * td * (td - 1.0));
}

// For each r, the t- and t(t-1)/2-weights of the detrending polynomial in each z_k:
// table[12 r + k] = sum_i kZ[k][i] t_i(r), table[12 r + 6 + k] = sum_i kZ[k][i] t_i (t_i - 1) / 2.
// Integers, exact in doubles below 2^53.
std::vector<double> polynomial_weights(std::size_t m) {
  std::vector<double> table(12 * m);
  const auto mi = static_cast<long long>(m);
  for (long long r = 0; r < mi; ++r) {
    const long long t[6] = {3 * mi - r, 2 * mi - r, mi - r, r, r + mi, r + 2 * mi};
    for (int k = 0; k < 6; ++k) {
      long long linear = 0, quadratic = 0;
      for (int i = 0; i < 6; ++i) {
        linear += kZ[k][i] * t[i];
        quadratic += kZ[k][i] * (t[i] * (t[i] - 1) / 2);
      }
      table[12 * static_cast<std::size_t>(r) + static_cast<std::size_t>(k)] =
          static_cast<double>(linear);
      table[12 * static_cast<std::size_t>(r) + 6 + static_cast<std::size_t>(k)] =
          static_cast<double>(quadratic);
    }
  }
  return table;
}

}  // namespace

IMUNOISE_CLONES long double reflected_window_sum(const double* ul, std::size_t m,
                                                 std::size_t count) {
  const std::size_t len = 3 * m;
  const std::size_t h = len / 2;
  const double len_d = static_cast<double>(len);
  const double slope_scale =
      1.0 / (static_cast<double>(h) * static_cast<double>(len - h));  // half-mean gap x h
  const double ramp_sum = 0.5 * len_d * (len_d - 1.0);                // sum of t, t < len
  const double md = static_cast<double>(m);
  const double scale = 1.0 / (6.0 * md * md * md);
  const std::vector<double> weights = polynomial_weights(m);
  long double total = 0.0L;
  for (std::size_t g = 0; g < count; g += kLanes) {
    const double* p = ul + g;
    const Vec8 base = load(p);
    const Vec8 end = load(p + len);
    const Vec8 slope = ((end - load(p + len - h)) - (load(p + h) - base)) * slope_scale;
    const Vec8 mean = ((end - base) - slope * ramp_sum) * (1.0 / len_d);
    const Vec8 twice_total = 2.0 * detrended_prefix(p, len, base, mean, slope);
    // z_k = sum_i kZ[k][i] ul[t_i] - (base sum_i kZ[k][i] - gamma_k 2T) - mean A_k - slope B_k.
    Vec8 constant[6];
    for (int k = 0; k < 6; ++k) {
      const int coefficient_sum = kZ[k][0] + kZ[k][1] + kZ[k][2] + kZ[k][3] + kZ[k][4] + kZ[k][5];
      constant[k] = base * static_cast<double>(coefficient_sum) -
                    twice_total * static_cast<double>(kGamma[k]);
    }
    Vec8 acc[6] = {};
    const double* w = weights.data();
    for (std::size_t r = 0; r < m; ++r, w += 12) {
      const Vec8 a0 = load(p + len - r);
      const Vec8 a1 = load(p + 2 * m - r);
      const Vec8 a2 = load(p + m - r);
      const Vec8 b0 = load(p + r);
      const Vec8 b1 = load(p + r + m);
      const Vec8 b2 = load(p + r + 2 * m);
      const Vec8 z0 = ((b0 + a0) - 3.0 * (a1 - a2)) - constant[0] - mean * w[0] - slope * w[6];
      const Vec8 z1 = ((b1 + a1) - 3.0 * (b0 + a2)) - constant[1] - mean * w[1] - slope * w[7];
      const Vec8 z2 = ((b2 + a2) - 3.0 * (b1 - b0)) - constant[2] - mean * w[2] - slope * w[8];
      const Vec8 z3 = (3.0 * (b1 - b2) - (a0 + b0)) - constant[3] - mean * w[3] - slope * w[9];
      const Vec8 z4 = (3.0 * (a0 + b2) - (a1 + b1)) - constant[4] - mean * w[4] - slope * w[10];
      const Vec8 z5 = (3.0 * (a1 - a0) - (a2 + b2)) - constant[5] - mean * w[5] - slope * w[11];
      acc[0] += z0 * z0;
      acc[1] += z1 * z1;
      acc[2] += z2 * z2;
      acc[3] += z3 * z3;
      acc[4] += z4 * z4;
      acc[5] += z5 * z5;
    }
    const Vec8 s = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + (acc[4] + acc[5]);
    const std::size_t lanes = count - g < kLanes ? count - g : kLanes;
    for (std::size_t lane = 0; lane < lanes; ++lane) total += s[lane] * scale;
  }
  return total;
}

}  // namespace imunoise::detail
