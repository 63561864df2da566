// Monte Carlo against the covariance model: a statistical test at every reported time.
//
// Tolerance. For each channel and time the Monte-Carlo mean square m = (1/n) sum x_i^2
// estimates the covariance model's variance s^2; its standard error se is estimated from the
// same runs (sums of x^4). For Gaussian x, var(x^2) = 2 s^4, so se ~ s^2 sqrt(2/n), and with
// n >= 300 the mean square is close to normal (chi^2_n skewness sqrt(8/n) <= 0.16). We accept
// |m - s^2| <= 4 se at every time: with 2 channels x 12 times the family-wise false-alarm rate
// is at most 24 x 6.3e-5 = 1.5e-3 (Bonferroni), and a model error of a few percent in variance
// would be caught with 2000 runs (se = 3.2 % of s^2). The same bound holds the sample mean
// to 0 (no deterministic term). The seed is fixed, so the test is deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "imunoise/nav/navigation.hpp"
#include "imunoise/units.hpp"

namespace imunoise::nav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Coefficient present(double v) {
  Coefficient c;
  c.value = v;
  c.identified = true;
  return c;
}

NavOptions tg100(std::size_t runs) {
  NavOptions o;
  o.duration_s = 3600.0;
  o.step_s = 300.0;
  o.latitude_rad = 58.5 * kDeg;
  o.runs = runs;
  o.seed = 12;
  o.models = {Model::covariance, Model::montecarlo};
  for (auto& a : o.axes) {
    a.coefficients.random_walk = present(8.9e-4 * kDeg);
    a.coefficients.bias_instability = present(5.9e-4 * kDeg);
    a.coefficients.rate_random_walk = present(0.15e-4 * kDeg);
  }
  o.axes[0].coefficients.quantization = present(1e-3 * kDeg);
  return o;
}

void expect_agreement(const NavOptions& o) {
  const NavResult r = navigation_error(o);
  const ModelSeries& cov = r.models[0];
  const ModelSeries& mc = r.models[1];
  const MonteCarloStats& st = *mc.montecarlo;
  const double radius = o.earth.radius_m;
  double worst = 0.0;
  for (std::size_t i = 1; i < cov.t_s.size(); ++i) {
    const double var_n = cov.north_m[i] * cov.north_m[i];
    const double var_e = cov.east_m[i] * cov.east_m[i];
    const double zn = (st.ms_north_m2[i] - var_n) / st.se_ms_north_m2[i];
    const double ze = (st.ms_east_m2[i] - var_e) / st.se_ms_east_m2[i];
    worst = std::max({worst, std::abs(zn), std::abs(ze)});
    EXPECT_LT(std::abs(zn), 4.0) << "north at t = " << cov.t_s[i];
    EXPECT_LT(std::abs(ze), 4.0) << "east at t = " << cov.t_s[i];
    EXPECT_LT(std::abs(st.mean_north_m[i]), 4.0 * st.se_mean_north_m[i]) << "t = " << cov.t_s[i];
    EXPECT_LT(std::abs(st.mean_east_m[i]), 4.0 * st.se_mean_east_m[i]) << "t = " << cov.t_s[i];
    // The standard error itself is what the Gaussian theory says, within its own noise.
    EXPECT_NEAR(st.se_ms_north_m2[i] / (var_n * std::sqrt(2.0 / static_cast<double>(o.runs))), 1.0, 0.35);
  }
  (void)radius;
  std::printf("montecarlo vs covariance, %zu runs: worst |z| = %.2f over %zu times\n", o.runs, worst,
              cov.t_s.size() - 1);
}

TEST(NavMonteCarlo, AgreesWithCovarianceWithinSamplingError) { expect_agreement(tg100(300)); }

// Two Gauss-Markov terms on every axis (a gmwm fit): the simulator's channel has one, the second
// is simulated as its own process and summed. The slow term (2e-3 deg/s, 600 s) dominates the
// 1 h error, so a Monte Carlo that dropped it would sit far below the covariance model (>> 4 se).
TEST(NavMonteCarlo, EveryGaussMarkovTermIsSimulated) {
  NavOptions o = tg100(300);
  for (auto& a : o.axes) {
    a.coefficients.bias_instability = {};
    a.coefficients.gauss_markov = {GaussMarkovTerm{present(1e-3 * kDeg), present(30.0)},
                                   GaussMarkovTerm{present(2e-3 * kDeg), present(600.0)}};
  }
  expect_agreement(o);
}

TEST(SlowNavMonteCarlo, AgreesWithCovarianceWithinSamplingError2000Runs) { expect_agreement(tg100(2000)); }

TEST(SlowNavMonteCarlo, AgreesWithoutEarthRateAtSixHours) {
  NavOptions o = tg100(300);
  o.duration_s = 6 * 3600.0;
  o.step_s = 1800.0;
  o.earth_rate = false;
  expect_agreement(o);
}

TEST(NavMonteCarlo, ResultDoesNotDependOnTheThreadCount) {
  NavOptions o = tg100(40);
  o.duration_s = 600.0;
  o.step_s = 60.0;
  o.models = {Model::montecarlo};
  o.threads = 1;
  const NavResult one = navigation_error(o);
  o.threads = 3;
  const NavResult three = navigation_error(o);
  EXPECT_EQ(one.models[0].north_m, three.models[0].north_m);
  EXPECT_EQ(one.models[0].east_m, three.models[0].east_m);
  EXPECT_EQ(one.models[0].montecarlo->se_ms_north_m2, three.models[0].montecarlo->se_ms_north_m2);
  o.seed = 13;
  const NavResult other = navigation_error(o);
  EXPECT_NE(one.models[0].north_m.back(), other.models[0].north_m.back());
}

// Drift and ramp on every axis: by default each run draws them as independent random
// constants per axis, the covariance model's reading, so the two agree by the same test. The
// navigation error is then linear in Gaussian constants and noise, so the Gaussian standard
// error of the header holds. 0.01 deg/s, as a user would give it: with the signed values the
// Monte Carlo answered 5736 km where the covariance answered 4860 km.
NavOptions drift_and_ramp(std::size_t runs) {
  NavOptions o = tg100(runs);
  for (auto& a : o.axes) {
    a.bias_rad_s = 0.01 * kDeg;
    a.coefficients.rate_ramp = present(2e-7 * kDeg);
  }
  return o;
}

TEST(NavMonteCarlo, RandomDriftAndRampPerAxisAgreeWithCovariance) { expect_agreement(drift_and_ramp(300)); }

// The signed reading answers another question (drifts on several axes add with their signs):
// it must disagree with the covariance, which shows the test above can fail.
TEST(NavMonteCarlo, SignedDriftsOnEveryAxisDisagreeWithCovariance) {
  NavOptions o = tg100(40);
  for (auto& a : o.axes) a.bias_rad_s = 0.01 * kDeg;
  o.signed_constants = true;
  const NavResult r = navigation_error(o);
  const ModelSeries& cov = r.models[0];
  const MonteCarloStats& st = *r.models[1].montecarlo;
  double worst_ms = 0.0, worst_mean = 0.0;
  for (std::size_t i = 1; i < cov.t_s.size(); ++i) {
    const double var_e = cov.east_m[i] * cov.east_m[i];
    worst_ms = std::max(worst_ms, std::abs(st.ms_east_m2[i] - var_e) / st.se_ms_east_m2[i]);
    worst_mean = std::max(worst_mean, std::abs(st.mean_east_m[i]) / st.se_mean_east_m[i]);
  }
  std::printf("signed drifts: worst |z| mean square %.1f, mean %.1f\n", worst_ms, worst_mean);
  EXPECT_GT(std::max(worst_ms, worst_mean), 4.0);
}

// A constant drift is the same in every run and exactly piecewise constant: the Monte Carlo
// then equals the covariance to rounding, which checks the discrete input matrix and the
// accumulation independently of any statistics.
// (Signed, one axis at a time: drifts on several axes add with their signs in a run, while the
// covariance model treats each as an independent drift of unknown sign.)
TEST(NavMonteCarlo, ConstantDriftIsReproducedExactly) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    NavOptions o = tg100(4);
    o.signed_constants = true;
    for (auto& a : o.axes) a = GyroAxisNoise{};
    o.axes[axis].bias_rad_s = -2.0 * units::deg_per_h_to_rad_per_s;
    const NavResult r = navigation_error(o);
    for (std::size_t i = 1; i < r.t_s.size(); ++i) {
      EXPECT_NEAR(r.models[1].north_m[i] / r.models[0].north_m[i], 1.0, 1e-9) << axis;
      EXPECT_NEAR(r.models[1].east_m[i] / r.models[0].east_m[i], 1.0, 1e-9) << axis;
      EXPECT_NEAR(std::abs(r.models[1].montecarlo->mean_north_m[i]) / r.models[0].north_m[i], 1.0, 1e-9) << axis;
    }
  }
}

}  // namespace
}  // namespace imunoise::nav
