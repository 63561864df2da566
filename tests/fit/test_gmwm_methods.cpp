// gmwm beside wls and ols on the same records (issue 24's side-by-side study): records from the
// tests' own generators (gmwm_test_support.hpp, kasdin_walter.hpp; nothing from src/sim), each
// fitted by the three methods from one octave curve. Printed: mean error, RMSE and 95 % coverage
// of every parameter a method reports; asserted: gmwm's coverage (the model it fits is the truth).
// Suite Slow*: minutes on 2 cores, outside CI (scripts/test_slow.sh); IMUNOISE_GMWM_RUNS sets the
// number of records (default 100). docs/fit.md has the measured tables.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <boost/math/distributions/binomial.hpp>

#include "gmwm_test_support.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/gmwm.hpp"
#include "kasdin_walter.hpp"

namespace imunoise::fit {
namespace methods_study {

/// One parameter's tally over the records: estimates against the truth, interval hits.
struct Tally {
  std::string label;
  double truth = 0.0;
  int runs = 0, covered = 0;
  double sum_rel = 0.0, sum_rel2 = 0.0;
  void add(double estimate, double lo, double hi) {
    ++runs;
    covered += std::isfinite(hi) && lo <= truth && truth <= hi;
    const double rel = estimate / truth - 1.0;
    sum_rel += rel;
    sum_rel2 += rel * rel;
  }
  void print() const {
    std::printf("  %-16s mean error %+8.2f %%  RMSE %8.2f %%  coverage %3d/%d\n", label.c_str(),
                100.0 * sum_rel / runs, 100.0 * std::sqrt(sum_rel2 / runs), covered, runs);
  }
};

int runs() { return std::getenv("IMUNOISE_GMWM_RUNS") ? std::atoi(std::getenv("IMUNOISE_GMWM_RUNS")) : 100; }

const Coefficient& power_law(const FitResult& r, int j) {
  switch (j) {
    case kN: return r.coefficients.random_walk;
    case kB: return r.coefficients.bias_instability;
    default: return r.coefficients.rate_random_walk;
  }
}

/// A reported term: the estimate (0 where not identified, the convention of every fit) and its
/// interval ([0, upper limit] where not identified).
void add_coefficient(Tally& t, const Coefficient& c) {
  t.add(c.identified ? c.value : 0.0, c.identified ? c.ci_low : 0.0, c.ci_high);
}

/// wls (the default, with its automatic extra terms) and ols (the paper's) on the power-law
/// terms of the truth (kN, kB, kK as listed in `terms`).
void add_power_law_fits(std::vector<Tally>& wls, std::vector<Tally>& ols, const std::vector<int>& terms,
                        const std::vector<DevPoint>& points, std::size_t n_phase, double tau0_s) {
  FitOptions w;
  const FitResult rw = fit_allan(points, n_phase, tau0_s, w);
  FitOptions o;
  o.method = Method::ols;
  const FitResult ro = fit_allan(points, n_phase, tau0_s, o);
  for (std::size_t i = 0; i < terms.size(); ++i) {
    add_coefficient(wls[i], power_law(rw, terms[i]));
    const Coefficient& c = power_law(ro, terms[i]);
    // ols: the paper's |coefficient| (sqrt |theta|), the estimate it printed.
    ols[i].add(std::sqrt(std::abs(ro.terms[terms[i]].theta)), c.identified ? c.ci_low : 0.0, c.ci_high);
  }
}

/// gmwm's estimates in the order of its terms: magnitude, then (GM) correlation time. The
/// intervals as reported (the convention of SlowGmwmMonteCarlo.Coverage3h); the estimate 0 for
/// a magnitude not identified, the fitted T_c for a GM term's correlation time.
void add_gmwm_fit(std::vector<Tally>& g, const GmwmResult& r) {
  std::size_t k = 0;
  for (const auto& t : r.terms) {
    const Coefficient& c = t.magnitude;
    g[k++].add(c.identified ? c.value : 0.0, c.ci_low, c.ci_high);
    if (t.kind == GmwmTerm::GM) g[k++].add(t.shape_fitted, t.shape.ci_low, t.shape.ci_high);
  }
}

/// IMUNOISE_GMWM_Z: one line per record with each parameter's estimate / truth and the side of
/// a miss (L: the truth below the interval, H: above).
void print_misses(int record, const std::vector<Tally>& g, const GmwmResult& r) {
  std::printf("record %d:", record);
  std::size_t k = 0;
  auto one = [&](double value, const Coefficient& c) {
    const double truth = g[k++].truth;
    const char side = truth < c.ci_low ? 'L' : truth > c.ci_high ? 'H' : '.';
    std::printf(" %.3g%s%c", value / truth, c.identified ? "" : "*", side);
  };
  for (const auto& t : r.terms) {
    one(t.magnitude_fitted, t.magnitude);
    if (t.kind == GmwmTerm::GM) one(t.shape_fitted, t.shape);
  }
  std::printf("  J %.1f/%zu\n", r.j_statistic, r.dof);
}

void print_study(const char* title, const std::vector<Tally>& g, const std::vector<Tally>& w,
                 const std::vector<Tally>& o) {
  std::printf("\n%s\n gmwm\n", title);
  for (const auto& t : g) t.print();
  std::printf(" wls (default)\n");
  for (const auto& t : w) t.print();
  std::printf(" ols (paper)\n");
  for (const auto& t : o) t.print();
}

/// Each gmwm parameter's coverage inside the binomial 99 % band around 0.95.
void expect_gmwm_coverage(const std::vector<Tally>& g) {
  for (const auto& t : g) {
    const boost::math::binomial_distribution<double> b(t.runs, 0.95);
    EXPECT_GE(t.covered, boost::math::quantile(b, 0.005)) << t.label;
    EXPECT_LE(t.covered, boost::math::quantile(boost::math::complement(b, 0.005))) << t.label;
  }
}

std::vector<Tally> tallies(const std::vector<std::pair<std::string, double>>& truth) {
  std::vector<Tally> v;
  for (const auto& [label, value] : truth) v.push_back(Tally{label, value});
  return v;
}

/// White + random walk + AR1 terms (rad/s units, 100 Hz, `hours`), gmwm fitted with the true
/// terms: N, K, one GM per AR1.
void ar1_study(const char* title, const std::vector<gmwm_test::Ar1Spec>& ar1, double hours, std::uint64_t seed0) {
  constexpr double tau0 = 0.01, n_coef = 1.7e-4, k_coef = 1e-5;
  std::vector<std::pair<std::string, double>> truth{{"N", n_coef}, {"K", k_coef}};
  std::string model = "N,K";
  for (std::size_t i = 0; i < ar1.size(); ++i) {
    truth.push_back({"GM" + std::to_string(i + 1) + " sigma", ar1[i].sigma});
    truth.push_back({"GM" + std::to_string(i + 1) + " T_c", ar1[i].tc_s});
    model += ",GM";
  }
  auto g = tallies(truth);
  auto w = tallies({truth[0], truth[1]});
  auto o = w;
  const auto n = static_cast<std::size_t>(hours * 3600.0 / tau0);
  // IMUNOISE_GMWM_FIRST=r: start at record r (one record: with IMUNOISE_GMWM_RUNS=r+1).
  const int first = std::getenv("IMUNOISE_GMWM_FIRST") ? std::atoi(std::getenv("IMUNOISE_GMWM_FIRST")) : 0;
  for (int r = first; r < runs(); ++r) {
    const auto rate = gmwm_test::make_rate(n, tau0, n_coef, k_coef, ar1, seed0 + static_cast<std::uint64_t>(r));
    const auto points = gmwm_test::octave_points(rate, tau0);
    const auto c = gmwm_test::curve_of(points, n + 1);
    GmwmOptions opt;
    parse_gmwm_terms(model, opt);
    const GmwmResult fit = fit_gmwm(c.m, c.avar, c.n_phase, tau0, opt);
    ASSERT_EQ(fit.terms.size(), 2 + ar1.size());
    add_gmwm_fit(g, fit);
    if (std::getenv("IMUNOISE_GMWM_Z")) print_misses(r, g, fit);
    add_power_law_fits(w, o, {kN, kK}, points, n + 1, tau0);
  }
  print_study(title, g, w, o);
  expect_gmwm_coverage(g);
}

TEST(SlowGmwmMethods, TwoAr1ADecadeApart3h) {
  ar1_study("white + random walk + AR1 (2e-4, 2 s) + AR1 (1e-4, 20 s), 3 h at 100 Hz",
            {{2e-4, 2.0}, {1e-4, 20.0}}, 3.0, 7000);
}

// DISABLED (2026-12-06, 100 records, seeds 8000-8099): GM2 T_c covered 85, GM3 sigma 82, GM3 T_c
// 77 of 100 (band [88, 100]); GM3 T_c mean error +673 %; 2026-12-07 after the settling: 84, 81, 76;
// after a profile can bring back a floored K: 85, 81, 80; after the profile set's other pieces:
// 92, 86, 83 (GM2 T_c in the band). What is left is the slowest term: K at its floor with the
// 50 s term carrying the random walk (T_c 6-14x the truth, the truth below the interval; on
// record 3 the true labelling is ~5 above the optimum, outside the rise), or its sigma fitted
// 1.4-1.7x the truth with a shorter T_c. The spurious fast term with K absorbing the slowest
// (records 2, 9, 10) is now an interval the other labelling widens:
// GmwmFit.AnotherLabellingAsGoodWidensTheIntervals; a floored K coming back in a profile:
// GmwmFit.AProfileCanBringBackATermAtItsFloor. 2026-12-08, with the profile of the cube-root
// score objective (gmwm_profile.cpp): GM3 sigma 93, GM3 T_c 92, every coverage in the band
// (GmwmFit.TheScoreProfileReachesPastTheLongScalesSkew); still DISABLED for its 24 minutes, past
// the slow label's 900 s timeout (docs/fit.md, "The score objective's profile").
TEST(SlowGmwmMethods, DISABLED_ThreeAr1ADecadeApart3h) {
  ar1_study("white + random walk + AR1 (3e-4, 0.5 s) + AR1 (2e-4, 5 s) + AR1 (1e-4, 50 s), 3 h at 100 Hz",
            {{3e-4, 0.5}, {2e-4, 5.0}, {1e-4, 50.0}}, 3.0, 8000);
}

/// The paper's TG-100 gyro 1 set (Table 2: N 8.9e-4 deg/sqrt(s), B 5.9e-4 deg/s, K 1.5e-5
/// deg/s/sqrt(s)), 6 h at 200 Hz, the flicker true 1/f to Nyquist (Kasdin-Walter), not the
/// continuous floor gmwm's B term assumes near the short end; gmwm fitted as N,B,K.
TEST(SlowGmwmMethods, Tg100SetWithKasdinWalterFlicker6h) {
  constexpr double rate_hz = 200.0, tau0 = 1.0 / rate_hz;
  constexpr double n_coef = 8.9e-4, b_coef = 5.9e-4, k_coef = 1.5e-5;
  const std::vector<std::pair<std::string, double>> truth{{"N", n_coef}, {"B", b_coef}, {"K", k_coef}};
  auto g = tallies(truth), w = tallies(truth), o = tallies(truth);
  const auto n = static_cast<std::size_t>(6.0 * 3600.0 * rate_hz);
  const fit_test::KasdinWalterFlicker flicker(n);
  std::mt19937_64 rng(9000);
  for (int r = 0; r < runs(); r += 2) {
    auto [a, b] = flicker.pair(rng, b_coef);
    for (auto* rate : {&a, &b}) {
      if (g[0].runs >= runs()) break;
      fit_test::add_white_and_random_walk(*rate, tau0, n_coef, k_coef, rng);
      const auto points = gmwm_test::octave_points(*rate, tau0);
      const auto c = gmwm_test::curve_of(points, n + 1);
      GmwmOptions opt;
      parse_gmwm_terms("N,B,K", opt);
      const GmwmResult fit = fit_gmwm(c.m, c.avar, c.n_phase, tau0, opt);
      ASSERT_EQ(fit.terms.size(), 3u);
      add_gmwm_fit(g, fit);
      add_power_law_fits(w, o, {kN, kB, kK}, points, n + 1, tau0);
    }
  }
  print_study("TG-100 gyro 1 set, Kasdin-Walter flicker, 6 h at 200 Hz", g, w, o);
  for (const auto& t : g) ASSERT_EQ(t.runs, runs()) << t.label;
  expect_gmwm_coverage(g);
}

}  // namespace methods_study
}  // namespace imunoise::fit
