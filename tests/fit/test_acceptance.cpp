// Acceptance study of the fit's accuracy and coverage: the simulated TG-100 gyro 1 of Table 2, 6 h at
// 200 Hz, fixed seeds 1..runs (default 50; IMUNOISE_FIT_RUNS overrides for the longer studies
// recorded in docs/fit.md). Every run is fitted by the three methods from the same octave
// curve; the table of mean error, RMSE and coverage is printed and asserted for wls.
// Study knobs (not used by CI): IMUNOISE_FIT_SEL (0 none, 1 aic, 2 bic), IMUNOISE_FIT_CORR
// (1: generalised least squares), IMUNOISE_FIT_NOR (0: fit R too).
// Cost: ~0.55 s per run in Release (simulation 6 h at 200 Hz + oadev + three fits).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fit/fit_test_support.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/fit/fit.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::fit_test;

struct Stats {
  std::vector<double> est[fit::kTermCount];
  int covered[fit::kTermCount] = {};
  int identified[fit::kTermCount] = {};
  double width[fit::kTermCount] = {};
  int runs = 0;
};

const Coefficient& coef(const NoiseCoefficients& c, int j) {
  switch (j) {
    case fit::kQ: return c.quantization;
    case fit::kN: return c.random_walk;
    case fit::kB: return c.bias_instability;
    case fit::kK: return c.rate_random_walk;
    default: return c.rate_ramp;
  }
}

void accumulate(Stats& s, const fit::FitResult& r, fit::Method method) {
  const double truth[fit::kTermCount] = {0.0, kN, kB, kK, 0.0};
  for (int j = 0; j < fit::kTermCount; ++j) {
    const auto& t = r.terms[j];
    // ols: the paper's |coefficient| (sqrt of |theta|); the others: the non-negative estimate.
    const double e = method == fit::Method::ols ? std::sqrt(std::abs(t.theta)) : t.estimate;
    s.est[j].push_back(e);
    const auto& c = coef(r.coefficients, j);
    const double lo = c.identified ? c.ci_low : 0.0;
    const double hi = c.ci_high;
    if (std::isfinite(hi) && lo <= truth[j] && truth[j] <= hi) ++s.covered[j];
    if (c.identified) ++s.identified[j];
    if (std::isfinite(hi) && truth[j] > 0) s.width[j] += (hi - lo) / truth[j];
  }
  ++s.runs;
}

struct Summary {
  double mean_err, rmse, sd, se, coverage, id_frac, width;
};

Summary summarize(const Stats& s, int j, double truth) {
  const auto n = static_cast<double>(s.est[j].size());
  double mean = 0, sq = 0;
  for (double e : s.est[j]) {
    mean += e;
    sq += (e - truth) * (e - truth);
  }
  mean /= n;
  double var = 0;
  for (double e : s.est[j]) var += (e - mean) * (e - mean);
  const double sd = std::sqrt(var / (n - 1));
  const double ref = truth > 0 ? truth : 1.0;
  return {(mean - truth) / ref, std::sqrt(sq / n) / ref, sd / ref, sd / std::sqrt(n) / ref,
          s.covered[j] / n, s.identified[j] / n, s.width[j] / n};
}

int runs_from_env() {
  const char* v = std::getenv("IMUNOISE_FIT_RUNS");
  return v != nullptr ? std::max(2, std::atoi(v)) : 50;
}

TEST(FitAcceptance, Tg100Gyro1SixHours) {
  const int runs = runs_from_env();
  const fit::Method methods[3] = {fit::Method::wls, fit::Method::ols, fit::Method::slope};
  Stats stats[3];
  int q_or_r_identified = 0;
  int with_scatter = 0, with_cut = 0;
  for (int run = 0; run < runs; ++run) {
    const auto phase = tg100_phase(6.0, 1 + static_cast<std::uint64_t>(run));
    std::vector<std::size_t> factors;
    for (std::size_t m = 1; 2 * m < phase.size(); m *= 2) factors.push_back(m);
    const auto curve = oadev(phase, 1.0 / kRateHz, factors);
    for (int k = 0; k < 3; ++k) {
      fit::FitOptions options;
      options.method = methods[k];
      if (const char* v = std::getenv("IMUNOISE_FIT_SEL")) options.selection = static_cast<fit::Selection>(std::atoi(v));
      if (const char* v = std::getenv("IMUNOISE_FIT_NOR")) options.terms[fit::kR] = std::atoi(v) == 0;
      if (const char* v = std::getenv("IMUNOISE_FIT_CORR")) options.use_correlation = std::atoi(v) != 0;
      // IMUNOISE_FIT_EXACT=1: the exact-model fit (no mismatch scatter, no short-tau cut).
      if (const char* v = std::getenv("IMUNOISE_FIT_EXACT"); v != nullptr && std::atoi(v) != 0) {
        options.model_mismatch = false;
        options.exclude_distorted = false;
        options.flicker_band_edge = false;
      }
      const auto r = fit::fit_allan(curve, phase.size(), 1.0 / kRateHz, options);
      accumulate(stats[k], r, methods[k]);
      if (k == 0) {
        with_scatter += r.summary.mismatch_scatter > 0.0;
        with_cut += !r.summary.excluded_taus.empty();
        q_or_r_identified += r.coefficients.quantization.identified || r.coefficients.rate_ramp.identified;
      }
    }
  }
  const double truth[fit::kTermCount] = {0.0, kN, kB, kK, 0.0};
  std::printf("\n%d runs, TG-100 gyro 1, 6 h at 200 Hz, octave taus, 95%% intervals\n", runs);
  std::printf("%-6s %-2s %10s %10s %10s %9s %9s %9s\n", "method", "", "mean err", "RMSE", "MC sd",
              "coverage", "ident.", "CI width");
  for (int k = 0; k < 3; ++k) {
    for (int j = fit::kQ; j <= fit::kR; ++j) {
      const auto s = summarize(stats[k], j, truth[j]);
      std::printf("%-6s %-2s %+9.2f%% %9.2f%% %9.2f%% %8.0f%% %8.0f%% %8.2f\n",
                  fit::method_name(methods[k]).c_str(), fit::term_name(j), 100 * s.mean_err,
                  100 * s.rmse, 100 * s.sd, 100 * s.coverage, 100 * s.id_frac, s.width);
    }
  }
  std::printf("wls: Q or R identified in %d of %d runs\n", q_or_r_identified, runs);
  std::printf("wls: mismatch scatter estimated in %d, short taus cut in %d of %d runs\n",
              with_scatter, with_cut, runs);
  // K^2 (the fitted variance coefficient) beside K: the square root of an unbiased but
  // widely scattered theta_K is biased low (Jensen), which is most of K's mean error.
  double k2_err = 0, k2_se = 0;
  {
    const auto& e = stats[0].est[fit::kK];
    double mean = 0, sq = 0;
    for (double v : e) mean += v * v / (kK * kK);
    mean /= static_cast<double>(e.size());
    for (double v : e) sq += (v * v / (kK * kK) - mean) * (v * v / (kK * kK) - mean);
    k2_se = std::sqrt(sq / static_cast<double>(e.size() - 1) / static_cast<double>(e.size()));
    k2_err = mean - 1.0;
    std::printf("wls: K^2 mean error %+.2f%% (standard error %.2f%%)\n", 100 * k2_err, 100 * k2_se);
  }

  // Assertions on the default method (the accepted bias, RMSE and coverage; docs/fit.md has the
  // 200-run study).
  const auto n = summarize(stats[0], fit::kN, kN);
  const auto b = summarize(stats[0], fit::kB, kB);
  const auto k = summarize(stats[0], fit::kK, kK);
  EXPECT_LT(std::abs(n.mean_err), 0.01);
  EXPECT_LT(std::abs(b.mean_err), 0.05);
  EXPECT_LT(std::abs(k.mean_err), 2.5 * k.se);
  EXPECT_LT(std::abs(k2_err), 2.5 * k2_se);
  // The plain weighted fit scatters K by ~60% (issue, measured): beat it.
  EXPECT_LT(k.rmse, 0.60);
  for (const auto& s : {n, b}) {
    EXPECT_GE(s.coverage, 0.90);
    EXPECT_LE(s.coverage, 0.98);
  }
  // K: 50/50 covered happens with probability 0.36 at a true coverage of 0.98 (the 200-run
  // study measured 0.98), so the upper bound cannot be asserted at 50 runs; the lower one is.
  EXPECT_GE(k.coverage, 0.90);
  // wls beats the paper's ols on B, the term the paper compares with the datasheet.
  EXPECT_LT(b.rmse, summarize(stats[1], fit::kB, kB).rmse);
  EXPECT_EQ(q_or_r_identified, 0);
}

}  // namespace
