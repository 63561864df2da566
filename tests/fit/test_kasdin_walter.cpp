// Coverage of the fit's intervals on records from an independent generator: flicker
// rate noise by the Kasdin-Walter fractional difference (tests/fit/kasdin_walter.hpp, no
// src/sim code) plus white and random-walk rate noise at the paper's gyro 1 (Table 2), 6 h at
// 200 Hz. The CI test runs 30 records of 1 h (the full 6 h study takes ~20 CPU-minutes
// for the 2^24-point transforms: IMUNOISE_KW_HOURS=6, numbers in docs/fit.md);
// IMUNOISE_KW_RUNS overrides the number of runs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "fit/fit_test_support.hpp"
#include "fit/kasdin_walter.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/phase.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::fit_test;

std::vector<std::size_t> octave(std::size_t n) {
  std::vector<std::size_t> f;
  for (std::size_t m = 1; 2 * m < n; m *= 2) f.push_back(m);
  return f;
}

TEST(KasdinWalter, FlickerFloorIsTheEq5Floor) {
  // Innovations of standard deviation B give the Allan floor (2 ln 2 / pi) B^2 (header): the
  // mean over 8 records of 2^18 samples at tau = 2^4..2^12 samples, each within 4 standard
  // errors of the record-to-record scatter plus 1 % (the discrete filter's Allan variance
  // exceeds the continuous floor by 0.46 % at m = 16 and less beyond: 1/f reaches Nyquist).
  const std::size_t n = std::size_t{1} << 18;
  const KasdinWalterFlicker gen(n);
  std::mt19937_64 rng(7);
  const double tau0 = 1.0;
  const std::vector<std::size_t> m = {16, 64, 256, 1024, 4096};
  std::vector<std::vector<double>> avar(m.size());
  for (int rec = 0; rec < 4; ++rec) {
    auto [a, b] = gen.pair(rng, 1.0);
    for (auto* r : {&a, &b}) {
      const auto phase = phase_from_rate(*r, tau0, 0.0);
      const auto pts = oadev(phase, tau0, m);
      for (std::size_t i = 0; i < m.size(); ++i) avar[i].push_back(pts[i].dev * pts[i].dev);
    }
  }
  const double floor = 2.0 * std::numbers::ln2 / std::numbers::pi;
  for (std::size_t i = 0; i < m.size(); ++i) {
    double mean = 0, sq = 0;
    for (double v : avar[i]) mean += v;
    mean /= static_cast<double>(avar[i].size());
    for (double v : avar[i]) sq += (v - mean) * (v - mean);
    const double se = std::sqrt(sq / static_cast<double>(avar[i].size() - 1) /
                                static_cast<double>(avar[i].size()));
    EXPECT_NEAR(mean, floor, 4.0 * se + 0.01 * floor) << "m = " << m[i];
  }
}

/// Allan variance of Kasdin-Walter flicker with unit innovations at averaging factor m (rate
/// samples), derived in the time domain (the library's band-edge term, src/fit/fit.cpp, uses a
/// frequency-domain quadrature; this is an independent check of it). The filter
/// (1 - z^-1)^(-1/2) has the impulse response h_0 = 1, h_k = h_{k-1} (k - 1/2) / k, and the
/// phase its running sum H(t) = h_0 + ... + h_{t-1}. The second difference of the phase over m
/// samples is sum_u e_u g_u with g_u = H(u + 2m) - 2 H(u + m) + H(u) (H = 0 for t <= 0) for the
/// innovation u samples before the first cluster, so sigma^2(m) = sum_u g_u^2 / (2 m^2). The
/// sum runs to U lags exactly; beyond, H(t) ~ 2 sqrt(t / pi) gives g_u ~ -m^2 u^-3/2 / (2
/// sqrt(pi)) and the tail m^4 / (8 pi U^2). 2/pi at m = 1 (closed form), tending to the eq. 5
/// floor 2 ln 2 / pi = 0.4413.
double kw_flicker_avar(std::size_t m) {
  const auto md = static_cast<double>(m);
  const std::size_t lags = std::max<std::size_t>(200 * m, 100000);
  std::vector<double> running(lags + 2 * m + 1, 0.0);  // running[t] = H(t)
  double h = 1.0;
  for (std::size_t t = 1; t < running.size(); ++t) {
    running[t] = running[t - 1] + h;
    h *= (static_cast<double>(t) - 0.5) / static_cast<double>(t);
  }
  auto at = [&](long long t) { return t <= 0 ? 0.0 : running[static_cast<std::size_t>(t)]; };
  const auto mm = static_cast<long long>(m);
  double sum = 0.0;
  for (long long u = 1 - 2 * mm; u <= static_cast<long long>(lags); ++u) {
    const double g = at(u + 2 * mm) - 2.0 * at(u + mm) + at(u);
    sum += g * g;
  }
  const double edge = static_cast<double>(lags) + md + 0.5;  // the tail's centre of mass
  sum += md * md * md * md / (8.0 * std::numbers::pi * edge * edge);
  return sum / (2.0 * md * md);
}

TEST(KasdinWalter, DiscreteFlickerExceedsTheFloorAtShortTaus) {
  const double floor = 2.0 * std::numbers::ln2 / std::numbers::pi;
  EXPECT_NEAR(kw_flicker_avar(1), 2.0 / std::numbers::pi, 1e-9);  // (4/pi)/2: closed form
  EXPECT_NEAR(kw_flicker_avar(1024) / floor, 1.0, 1e-5);
  // docs/fit.md's excess over the floor: 44 % at m = 1, 15 % at 2, 5 % at 4, 1.5 % at 8.
  const double excess[4] = {0.443, 0.154, 0.050, 0.015};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(kw_flicker_avar(std::size_t{1} << i) / floor - 1.0, excess[i], 0.001) << (1 << i);
  }
}

// The expected (noise-free) curve of the independent generator, fitted: the flicker's excess
// over the continuous floor at the shortest taus is the only model difference.
TEST(KasdinWalter, ExpectedCurveBiasOfN) {
  const double tau0 = 1.0 / kRateHz;
  const auto n_phase = static_cast<std::size_t>(6.0 * 3600.0 * kRateHz) + 1;
  std::vector<DevPoint> pts;
  for (std::size_t m = 1; 2 * m < n_phase; m *= 2) {
    DevPoint p;
    p.m = m;
    p.tau_s = static_cast<double>(m) * tau0;
    const double flicker = m <= 4096 ? kw_flicker_avar(m) : 2.0 * std::numbers::ln2 / std::numbers::pi;
    p.dev = std::sqrt(kN * kN / p.tau_s + kB * kB * flicker + kK * kK * p.tau_s / 3.0);
    pts.push_back(p);
  }
  const auto r = fit::fit_allan(pts, n_phase, tau0, fit::FitOptions{});
  const auto& c = r.coefficients.random_walk;
  const double sd = 0.5 * (c.ci_high - c.ci_low) / 1.96;
  const double bias = r.terms[fit::kN].estimate - kN;
  std::printf("expected Kasdin-Walter curve, 6 h: N bias %+.4f%% = %+.2f interval sd; B %+.3f%%\n",
              100 * bias / kN, bias / sd, 100 * (r.terms[fit::kB].estimate / kB - 1));
  // The bias must be small against the interval, or the coverage cannot hold.
  EXPECT_LT(std::abs(bias / sd), 0.75);
}

struct Coverage {
  int runs = 0;
  int covered[fit::kTermCount] = {};
  std::vector<double> z[fit::kTermCount];  // (estimate - truth) / (interval half-width / 1.96)
  std::vector<double> est[fit::kTermCount];
};

int runs_from_env(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::max(2, std::atoi(v)) : fallback;
}

// Gyro 1 of the paper by the independent generator, 6 h at 200 Hz.
Coverage kasdin_walter_study(int runs, const fit::FitOptions& options) {
  const double tau0 = 1.0 / kRateHz;
  const char* hours_env = std::getenv("IMUNOISE_KW_HOURS");
  const double hours = hours_env != nullptr ? std::atof(hours_env) : 1.0;
  const auto n = static_cast<std::size_t>(hours * 3600.0 * kRateHz);
  const KasdinWalterFlicker gen(n);
  const auto factors = octave(n + 1);
  const double truth[fit::kTermCount] = {0.0, kN, kB, kK, 0.0};
  Coverage c;
  std::mt19937_64 rng(20261201);
  for (int run = 0; run < runs; run += 2) {
    auto [a, b] = gen.pair(rng, kB);
    for (auto* rate : {&a, &b}) {
      if (c.runs == runs) break;
      add_white_and_random_walk(*rate, tau0, kN, kK, rng);
      const auto phase = phase_from_rate(*rate, tau0, 0.0);
      const auto pts = oadev(phase, tau0, factors);
      const auto r = fit::fit_allan(pts, phase.size(), tau0, options);
      for (int j = fit::kN; j <= fit::kK; ++j) {
        const auto& co = fit::coefficient(r.coefficients, j);
        const double lo = co.identified ? co.ci_low : 0.0;
        if (lo <= truth[j] && truth[j] <= co.ci_high) ++c.covered[j];
        const double e = r.terms[j].estimate;
        const double half = e >= truth[j] ? e - lo : co.ci_high - e;
        c.z[j].push_back(half > 0 ? 1.96 * (e - truth[j]) / half : 0.0);
        c.est[j].push_back(e);
      }
      ++c.runs;
      if (std::getenv("IMUNOISE_KW_VERBOSE") != nullptr) {
        std::printf("run %d: N %.6g [%.6g %.6g] z %+.2f B %.4g K %.4g chi2/dof %.3g scatter %.3g "
                    "cut %zu\n",
                    c.runs, r.terms[fit::kN].estimate, r.coefficients.random_walk.ci_low,
                    r.coefficients.random_walk.ci_high, c.z[fit::kN].back(),
                    r.terms[fit::kB].estimate, r.terms[fit::kK].estimate, r.summary.chi2_dof,
                    r.summary.mismatch_scatter, r.summary.excluded_taus.size());
        for (const auto& p : r.residuals) {
          if (p.tau_s < 0.1) std::printf("   tau %g resid/sd %+.2f used %d\n", p.tau_s, p.normalized, p.used);
        }
      }
    }
  }
  std::printf("\n%d runs, Kasdin-Walter flicker + white + random walk (gyro 1), %g h at 200 Hz\n",
              c.runs, hours);
  for (int j = fit::kN; j <= fit::kK; ++j) {
    double mean = 0, sq = 0, zsq = 0;
    for (double e : c.est[j]) mean += e;
    mean /= c.runs;
    for (double e : c.est[j]) sq += (e - mean) * (e - mean);
    for (double zz : c.z[j]) zsq += zz * zz;
    std::printf("%s: mean err %+.3f%%, MC sd %.3f%%, coverage %d/%d, rms z %.2f\n",
                fit::term_name(j), 100 * (mean / truth[j] - 1),
                100 * std::sqrt(sq / (c.runs - 1)) / truth[j], c.covered[j], c.runs,
                std::sqrt(zsq / c.runs));
  }
  return c;
}

TEST(SlowKasdinWalter, Tg100Gyro1Coverage) {
  const int runs = runs_from_env("IMUNOISE_KW_RUNS", 30);
  fit::FitOptions options;
  if (const char* v = std::getenv("IMUNOISE_FIT_EXACT"); v != nullptr && std::atoi(v) != 0) {
    options.model_mismatch = false;
    options.exclude_distorted = false;
    options.flicker_band_edge = false;
  }
  const auto c = kasdin_walter_study(runs, options);
  ASSERT_EQ(c.runs, runs);
  // Coverage of the 95 % intervals: with 30 runs at a true 0.95 the count is Binomial(30, 0.95)
  // (mean 28.5, sd 1.19); at least 24 of 30 must cover: P(count <= 23) = 0.06 % is the false
  // failure rate over seeds (the seed is fixed). Scaled for other run counts (3.8 sd).
  const int need = static_cast<int>(std::ceil(runs * 0.95 - 3.8 * std::sqrt(runs * 0.95 * 0.05)));
  for (int j = fit::kN; j <= fit::kK; ++j) {
    EXPECT_GE(c.covered[j], need) << fit::term_name(j);
  }
}

}  // namespace
