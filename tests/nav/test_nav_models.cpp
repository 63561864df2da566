// Navigation error models against independent closed forms (references.md, navigation section)
// and against each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "imunoise/error.hpp"
#include "imunoise/nav/models.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/paper.hpp"
#include "imunoise/nav/schuler.hpp"
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

// Options with noise on the east (y) gyro only: it drives the north channel (path).
NavOptions east_only(Model model, double hours = 1.0) {
  NavOptions o;
  o.duration_s = hours * 3600.0;
  o.models = {model};
  o.earth_rate = false;
  o.latitude_rad = 58.5 * kDeg;
  return o;
}

double path_at_end(const NavOptions& o) { return navigation_error(o).models.front().north_m.back(); }

// --- acceptance: references.md check values at 1 h (each within 0.5 %) -----------------------

TEST(NavAcceptance, ConstantEastDriftOneDegPerHourGives135p5km) {
  for (Model m : {Model::schuler, Model::covariance}) {
    NavOptions o = east_only(m);
    o.axes[1].bias_rad_s = 1.0 * units::deg_per_h_to_rad_per_s;
    EXPECT_NEAR(path_at_end(o) / 135.5e3, 1.0, 0.005) << model_name(m);
  }
}

// references.md quotes Titterton's "0.72 nmi (1.33 km)" for 0.01 deg/h. The error is linear in
// the drift, so with the constants that give 135.5 km for 1 deg/h it must be 1.355 km (0.7317
// nmi); 1.33 km is 1.9 % below that, i.e. a rounding of the book's (0.72 nmi = 1.333 km). We
// test the value consistent with 135.5 km, within 0.5 %, and the exact linearity.
TEST(NavAcceptance, ConstantDriftHundredthDegPerHourGives1p355km) {
  for (Model m : {Model::schuler, Model::covariance}) {
    NavOptions o = east_only(m);
    o.axes[1].bias_rad_s = 0.01 * units::deg_per_h_to_rad_per_s;
    const double small = path_at_end(o);
    EXPECT_NEAR(small / 1.355e3, 1.0, 0.005) << model_name(m);
    o.axes[1].bias_rad_s = 1.0 * units::deg_per_h_to_rad_per_s;
    EXPECT_NEAR(path_at_end(o) / small, 100.0, 1e-9) << model_name(m);
  }
}

TEST(NavAcceptance, AngleRandomWalkGives8p33km) {
  for (Model m : {Model::schuler, Model::covariance}) {
    NavOptions o = east_only(m);
    o.axes[1].coefficients.random_walk = present(8.9e-4 * kDeg);
    EXPECT_NEAR(path_at_end(o) / 8.33e3, 1.0, 0.005) << model_name(m);
  }
}

TEST(NavAcceptance, RateRandomWalkGives214p7km) {
  for (Model m : {Model::schuler, Model::covariance}) {
    NavOptions o = east_only(m);
    o.axes[1].coefficients.rate_random_walk = present(1.5e-5 * kDeg);
    EXPECT_NEAR(path_at_end(o) / 214.7e3, 1.0, 0.005) << model_name(m);
  }
}

TEST(NavAcceptance, PaperModelReproducesPublishedLongitude) {
  NavOptions o = east_only(Model::paper);
  o.axes[1].coefficients.random_walk = present(8.9e-4 * kDeg);  // gyro 1, Table 2
  const NavResult r = navigation_error(o);
  const double lon_deg = r.models.front().lon_rad.back() / kDeg;
  EXPECT_NEAR(lon_deg, 3.9, 0.05);  // published to 2 digits
  // ... and the other two published figures are not reproduced by the same sigma_eps.
  EXPECT_GT(r.models.front().lat_rad.back() / kDeg, 2 * 0.37);
  EXPECT_GT(r.models.front().north_m.back(), 10 * 22.6e3);
}

TEST(NavAcceptance, SchulerFrequencyAndPeriod) {
  const double w0 = schuler::frequency_rad_s(9.81, 6.380e6);
  EXPECT_NEAR(w0, 1.24001e-3, 1e-8);
  EXPECT_NEAR(2 * std::numbers::pi / w0 / 60.0, 84.45, 0.01);
}

// --- covariance equals the closed forms where they apply (single channel, Earth rate off) ---

void expect_covariance_equals_schuler(NavOptions o, double tol, double from_s = 600.0) {
  o.models = {Model::schuler, Model::covariance};
  o.earth_rate = false;
  const NavResult r = navigation_error(o);
  const ModelSeries& s = r.models[0];
  const ModelSeries& c = r.models[1];
  ASSERT_EQ(s.t_s.size(), c.t_s.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < s.t_s.size(); ++i) {
    if (s.t_s[i] < from_s) continue;
    worst = std::max({worst, std::abs(c.north_m[i] / s.north_m[i] - 1), std::abs(c.east_m[i] / s.east_m[i] - 1)});
    EXPECT_NEAR(c.north_m[i] / s.north_m[i], 1.0, tol) << "north at t = " << s.t_s[i];
    EXPECT_NEAR(c.east_m[i] / s.east_m[i], 1.0, tol) << "east at t = " << s.t_s[i];
  }
  std::printf("covariance vs closed form: worst relative difference %.3g\n", worst);
}

NavOptions two_channel(double hours = 2.0) {
  NavOptions o;
  o.duration_s = hours * 3600.0;
  o.step_s = 300.0;
  o.latitude_rad = 58.5 * kDeg;
  return o;
}

TEST(NavCovariance, EqualsClosedFormPerTerm) {
  struct Case {
    const char* name;
    void (*set)(GyroAxisNoise&);
  };
  const Case cases[] = {
      {"bias", [](GyroAxisNoise& a) { a.bias_rad_s = 2.0 * units::deg_per_h_to_rad_per_s; }},
      {"ramp", [](GyroAxisNoise& a) { a.coefficients.rate_ramp = present(1e-7 * kDeg); }},
      {"N", [](GyroAxisNoise& a) { a.coefficients.random_walk = present(8.9e-4 * kDeg); }},
      {"K", [](GyroAxisNoise& a) { a.coefficients.rate_random_walk = present(1.5e-5 * kDeg); }},
      {"B", [](GyroAxisNoise& a) { a.coefficients.bias_instability = present(5.9e-4 * kDeg); }},
      {"Q", [](GyroAxisNoise& a) { a.coefficients.quantization = present(1e-3 * kDeg); }},
      {"GM", [](GyroAxisNoise& a) {
         GaussMarkovTerm gm;
         gm.sigma = present(1e-3 * kDeg);
         gm.correlation_time_s = present(300.0);
         a.coefficients.gauss_markov = {gm};
       }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    NavOptions o = two_channel();
    c.set(o.axes[0]);
    c.set(o.axes[1]);
    expect_covariance_equals_schuler(o, 1e-6);
  }
}

TEST(NavCovariance, EqualsClosedFormForTheTg100Gyro1AndDifferentAxes) {
  NavOptions o = two_channel(6.0);
  o.step_s = 600.0;
  o.axes[1].coefficients.random_walk = present(8.9e-4 * kDeg);
  o.axes[1].coefficients.bias_instability = present(5.9e-4 * kDeg);
  o.axes[1].coefficients.rate_random_walk = present(0.15e-4 * kDeg);
  o.axes[0].coefficients.random_walk = present(8.6e-4 * kDeg);
  o.axes[0].bias_rad_s = 0.5 * units::deg_per_h_to_rad_per_s;
  o.axes[2].coefficients.random_walk = present(1e-2 * kDeg);  // down gyro: no effect without Earth rate
  expect_covariance_equals_schuler(o, 1e-6);
}

TEST(NavCovariance, EarthRateChangesTheOneHourErrorByAFewPercent) {
  NavOptions o = two_channel(1.0);
  o.step_s = 60.0;
  for (auto& a : o.axes) {
    a.coefficients.random_walk = present(8.9e-4 * kDeg);
    a.coefficients.bias_instability = present(5.9e-4 * kDeg);
    a.coefficients.rate_random_walk = present(0.15e-4 * kDeg);
  }
  o.models = {Model::schuler, Model::covariance};
  const NavResult r = navigation_error(o);
  const double ratio = r.models[1].radial_m.back() / r.models[0].radial_m.back();
  std::printf("Earth rate on / off, radial error at 1 h: %.5f (north %.5f, east %.5f)\n", ratio,
              r.models[1].north_m.back() / r.models[0].north_m.back(),
              r.models[1].east_m.back() / r.models[0].east_m.back());
  EXPECT_NEAR(ratio, 1.0, 0.05);
}

TEST(NavCovariance, StaysSymmetricAndPositiveSemiDefinite) {
  NavOptions o = two_channel(6.0);
  for (auto& a : o.axes) {
    a.coefficients.random_walk = present(8.9e-4 * kDeg);
    a.coefficients.bias_instability = present(5.9e-4 * kDeg);
    a.coefficients.rate_random_walk = present(0.15e-4 * kDeg);
    a.coefficients.quantization = present(1e-4 * kDeg);
    a.bias_rad_s = 1e-4;
  }
  o.models = {Model::covariance};
  const NavResult r = navigation_error(o);
  const CovarianceCheck& c = *r.models[0].covariance_check;
  EXPECT_EQ(c.max_asymmetry, 0.0);
  EXPECT_GT(c.min_eigenvalue_ratio, -1e-12);
}

TEST(NavCovariance, DoublingEqualsStepByStepPropagation) {
  NavOptions o = two_channel(1.0);
  o.step_s = 600.0;
  for (auto& a : o.axes) {  // 13 states: cheap enough step by step under the sanitizers
    a.coefficients.random_walk = present(8.9e-4 * kDeg);
    a.coefficients.rate_random_walk = present(0.15e-4 * kDeg);
    a.bias_rad_s = 1e-6;
  }
  o.axes[1].coefficients.gauss_markov = {GaussMarkovTerm{present(1e-5), present(300.0)}};
  o.models = {Model::covariance};
  const NavResult fast = navigation_error(o);
  o.covariance_per_step = true;
  const NavResult slow = navigation_error(o);
  for (std::size_t i = 1; i < fast.t_s.size(); ++i) {
    EXPECT_NEAR(fast.models[0].radial_m[i] / slow.models[0].radial_m[i], 1.0, 1e-11);
  }
}

// Every Gauss-Markov term of an axis (a gmwm fit may have several) reaches the model: the error
// model is linear in independent noises, so two terms add in variance exactly; a model that took
// only the first term would give the first term's error alone.
TEST(NavCovariance, EveryGaussMarkovTermAddsInVariance) {
  const GaussMarkovTerm fast{present(1e-3 * kDeg), present(30.0)};
  const GaussMarkovTerm slow{present(2e-3 * kDeg), present(600.0)};
  auto run = [](std::vector<GaussMarkovTerm> terms, Model model) {
    NavOptions o = east_only(model);
    o.step_s = 300.0;
    o.axes[1].coefficients.gauss_markov = std::move(terms);
    return navigation_error(o).models.front();
  };
  for (Model model : {Model::covariance, Model::schuler}) {
    const ModelSeries one = run({fast}, model), other = run({slow}, model), both = run({fast, slow}, model);
    for (std::size_t i = 1; i < both.t_s.size(); ++i) {
      const double sum = one.north_m[i] * one.north_m[i] + other.north_m[i] * other.north_m[i];
      EXPECT_NEAR(both.north_m[i] * both.north_m[i] / sum, 1.0, 1e-9) << model_name(model) << " t = " << both.t_s[i];
    }
    EXPECT_GT(both.north_m.back(), 1.5 * one.north_m.back()) << model_name(model);
  }
  // The document lists both, by correlation time.
  NavOptions o = east_only(Model::covariance);
  o.axes[1].coefficients.gauss_markov = {fast, slow};
  const NavResult r = navigation_error(o);
  ASSERT_EQ(r.terms[1].gauss_markov.size(), 2u);
  EXPECT_EQ(r.terms[1].gauss_markov[1].time_s, 600.0);
}

// --- closed forms: limits and the switch to power series ------------------------------------

TEST(NavSchuler, SeriesAndClosedFormMeetAtTheSwitch) {
  const double w0 = 1.24001e-3;
  const double t = 1.0 / w0;
  const double d = 1e-9 * t;
  auto rel = [](double a, double b) { return std::abs(a / b - 1.0); };
  EXPECT_LT(rel(schuler::constant_drift_rad(1.0, t - d, w0), schuler::constant_drift_rad(1.0, t + d, w0)), 1e-8);
  EXPECT_LT(rel(schuler::rate_ramp_rad(1.0, t - d, w0), schuler::rate_ramp_rad(1.0, t + d, w0)), 1e-8);
  EXPECT_LT(rel(schuler::white_rad(1.0, t - d, w0), schuler::white_rad(1.0, t + d, w0)), 1e-8);
  EXPECT_LT(rel(schuler::random_walk_rad(1.0, t - d, w0), schuler::random_walk_rad(1.0, t + d, w0)), 1e-8);
  // Short times: the leading terms of the response, c w0^2 t^3 / 6 and N w0^2 sqrt(t^5 / 20).
  const double ts = 10.0;
  EXPECT_LT(rel(schuler::constant_drift_rad(1.0, ts, w0), w0 * w0 * ts * ts * ts / 6.0), 1e-4);
  EXPECT_LT(rel(schuler::white_rad(1.0, ts, w0), w0 * w0 * std::sqrt(std::pow(ts, 5) / 20.0)), 1e-4);
}

TEST(NavSchuler, GaussMarkovLimits) {
  const double w0 = 1.24001e-3, t = 3600.0, sigma = 1e-5;
  // T >> t: a constant drift of RMS sigma.
  EXPECT_NEAR(schuler::gauss_markov_rad(sigma, 1e9, t, w0) / schuler::constant_drift_rad(sigma, t, w0), 1.0, 1e-5);
  // T << t: white noise of intensity 2 sigma^2 T.
  const double tc = 0.01;
  EXPECT_NEAR(schuler::gauss_markov_rad(sigma, tc, t, w0) /
                  schuler::white_rad(sigma * std::sqrt(2 * tc), t, w0),
              1.0, 1e-4);
}

TEST(NavSchuler, QuantizationIsBoundedAndSmall) {
  const double w0 = 1.24001e-3, q = 1e-6;
  // Its dominant part is the last sample's angle noise through the loop: Q (1 - cos w0 t).
  const double v = schuler::quantization_rad(q, 1.0, 3600.0, w0);
  EXPECT_NEAR(v / (q * (1.0 - std::cos(w0 * 3600.0))), 1.0, 0.01);
}

TEST(NavSchuler, QuantizationClosedSumEqualsTheDirectSum) {
  // Beyond k w0 h = 0.5 the sum of sin^2 is in closed form: compare with the defining formula.
  const double w0 = 1.24001e-3, q = 1e-6, h = 0.5;
  for (double t : {500.0, 3600.0, 21600.0}) {
    const long k = std::lround(t / h);
    const double xh = w0 * h;
    auto s = [](double x) { return x - std::sin(x); };
    const double a1 = s(xh) / w0, ak = (s(xh * static_cast<double>(k)) - s(xh * static_cast<double>(k - 1))) / w0;
    double sum = 0.0;
    for (long m = 1; m < k; ++m) sum += std::pow(std::sin(xh * static_cast<double>(m)), 2);
    const double g = 4 * std::pow(std::sin(xh / 2), 2) / w0;
    const double direct = (q / h) * std::sqrt(a1 * a1 + ak * ak + g * g * sum);
    EXPECT_NEAR(schuler::quantization_rad(q, h, t, w0) / direct, 1.0, 1e-9) << t;
  }
}

TEST(NavPaper, InversionsReturnTheInput) {
  const double w0 = 1.24001e-3;
  const double eps = 8.9e-4 * kDeg;
  EXPECT_NEAR(paper::sigma_eps_for_longitude(paper::longitude_rad(eps, 3600, w0), 3600, w0) / eps, 1.0, 1e-14);
  EXPECT_NEAR(paper::sigma_eps_for_latitude(paper::latitude_rad(eps, 3600, w0), 3600, w0) / eps, 1.0, 1e-14);
  EXPECT_NEAR(paper::sigma_eps_for_path(paper::path_m(eps, 3600, w0, 6.38e6), 3600, w0, 6.38e6) / eps, 1.0, 1e-14);
}

// --- bad input --------------------------------------------------------------------------------

TEST(NavBadInput, OptionsAreCheckedWithAClearMessage) {
  auto message = [](const NavOptions& o) {
    try {
      navigation_error(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  NavOptions o = east_only(Model::schuler);
  o.axes[1].coefficients.random_walk = present(1e-5);
  NavOptions bad = o;
  bad.duration_s = 0.0;
  EXPECT_NE(message(bad).find("duration"), std::string::npos);
  bad.duration_s = -3600.0;
  EXPECT_NE(message(bad).find("duration"), std::string::npos);
  bad = o;
  bad.latitude_rad = 91.0 * kDeg;
  EXPECT_NE(message(bad).find("latitude"), std::string::npos);
  bad = o;
  bad.axes[1].coefficients.random_walk = Coefficient{};
  EXPECT_NE(message(bad).find("no noise term"), std::string::npos);
  bad = o;
  bad.axes[2].coefficients.quantity = Quantity::acceleration;
  EXPECT_NE(message(bad).find("not a gyro's"), std::string::npos);
  bad = o;
  bad.step_s = 0.5;
  EXPECT_NE(message(bad).find("--step"), std::string::npos);
  bad = o;
  bad.models = {Model::paper};
  bad.axes[1].coefficients.random_walk = Coefficient{};
  bad.axes[1].bias_rad_s = 1e-6;
  EXPECT_NE(message(bad).find("--sigma-eps"), std::string::npos);
}

TEST(NavBadInput, AtThePoleLongitudeIsUndefinedButPathIsReported) {
  NavOptions o = east_only(Model::covariance);
  o.earth_rate = true;
  o.latitude_rad = std::numbers::pi / 2;
  o.axes[1].coefficients.random_walk = present(8.9e-4 * kDeg);
  o.models = {Model::paper, Model::schuler, Model::covariance};
  const NavResult r = navigation_error(o);
  EXPECT_FALSE(r.longitude_defined);
  for (const auto& m : r.models) {
    EXPECT_TRUE(m.lon_rad.empty());
    EXPECT_TRUE(std::isfinite(m.north_m.back()));
    EXPECT_GT(m.north_m.back(), 0.0);
  }
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.back().find("longitude is undefined"), std::string::npos);
}

TEST(NavBadInput, AbsentTermsAreNamed) {
  NavOptions o = east_only(Model::schuler);
  o.axes[1].coefficients.random_walk = present(1e-5);
  const NavResult r = navigation_error(o);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.front().find("K (all axes)"), std::string::npos);
  EXPECT_NE(r.notes.front().find("N (x,z)"), std::string::npos);
}

}  // namespace
}  // namespace imunoise::nav
