// Theory: closed forms against eq. 4 integrated from the PSD, special values, the flicker
// bank's floor accuracy over its stated range.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/sim/flicker.hpp"
#include "imunoise/sim/gauss_markov.hpp"
#include "imunoise/sim/theory.hpp"

using namespace imunoise::sim;

namespace {

std::vector<double> log_grid(double lo, double hi, int per_decade) {
  std::vector<double> out;
  const int n = static_cast<int>(std::ceil(std::log10(hi / lo) * per_decade));
  for (int i = 0; i <= n; ++i) out.push_back(std::min(hi, lo * std::pow(10.0, static_cast<double>(i) / per_decade)));
  return out;
}

NoiseModel tg100_gyro1() {
  NoiseModel m;
  m.n_unit_sqrt_s = 8.9e-4;
  m.b_unit = 5.9e-4;
  m.k_unit_per_sqrt_s = 1.5e-5;
  m.flicker_tau_min_s = 0.005;
  m.flicker_tau_max_s = 21600.0;
  return m;
}

}  // namespace

TEST(Theory, ClosedFormsOfEachTerm) {
  NoiseModel m;
  m.q_unit_s = 2.0;
  m.n_unit_sqrt_s = 3.0;
  m.k_unit_per_sqrt_s = 5.0;
  m.r_unit_per_s = 7.0;
  const AllanTerms t = allan_variance_terms(m, 4.0);
  EXPECT_DOUBLE_EQ(t.q, 3.0 * 4.0 / 16.0);
  EXPECT_DOUBLE_EQ(t.n, 9.0 / 4.0);
  EXPECT_DOUBLE_EQ(t.k, 25.0 * 4.0 / 3.0);
  EXPECT_DOUBLE_EQ(t.r, 49.0 * 16.0 / 2.0);
  // Read-offs of references.md: sigma(sqrt(3)) = Q, sigma(1) = N, sigma(3) = K, sigma(sqrt(2)) = R.
  NoiseModel q;
  q.q_unit_s = 2.0;
  EXPECT_NEAR(std::sqrt(allan_variance(q, std::sqrt(3.0))), 2.0, 1e-15);
  NoiseModel k;
  k.k_unit_per_sqrt_s = 5.0;
  EXPECT_NEAR(std::sqrt(allan_variance(k, 3.0)), 5.0, 1e-14);
  NoiseModel r;
  r.r_unit_per_s = 7.0;
  EXPECT_NEAR(std::sqrt(allan_variance(r, std::sqrt(2.0))), 7.0, 1e-14);
  NoiseModel b;
  b.b_unit = 1.0;
  EXPECT_NEAR(std::sqrt(nominal_allan_variance(b, 123.0)), kFlickerFloorPerB, 1e-15);
}

TEST(Theory, GaussMarkovMatchesIeee952FormAndItsPeak) {
  const double sigma = 0.3, t_c = 2.0;
  for (const double tau : log_grid(1e-4, 1e4, 7)) {
    const double x = tau / t_c;
    const double qc = 2.0 * sigma * sigma / t_c;
    const double ieee = qc * t_c * t_c / tau * (1.0 - t_c / (2.0 * tau) * (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x)));
    // The IEEE form cancels catastrophically for tau << T; compare where it is well conditioned.
    if (x > 0.05) {
      EXPECT_NEAR(gauss_markov_allan_variance(sigma, t_c, tau), ieee, 1e-12 * ieee) << tau;
    }
  }
  // Small-tau asymptote 2 sigma^2 tau / (3T) (rate random walk) and large-tau 2 sigma^2 T / tau.
  EXPECT_NEAR(gauss_markov_allan_variance(sigma, t_c, 1e-7), 2 * sigma * sigma * 1e-7 / (3 * t_c), 1e-13);
  EXPECT_NEAR(gauss_markov_allan_variance(sigma, t_c, 1e7) / (2 * sigma * sigma * t_c / 1e7), 1.0, 1e-6);
  // Peak 0.617364 sigma at tau = 1.892618 T (60-digit mpmath; references.md: "0.618 at 1.89").
  double best = 0, best_tau = 0;
  for (double tau = 3.78; tau < 3.80; tau += 1e-6) {
    const double d = std::sqrt(gauss_markov_allan_variance(sigma, t_c, tau));
    if (d > best) {
      best = d;
      best_tau = tau;
    }
  }
  EXPECT_NEAR(best / sigma, 0.61736428314444137, 1e-12);
  EXPECT_NEAR(best_tau / t_c, 1.8926178329, 1e-4);
}

TEST(Theory, GaussMarkovSeriesIsAccurateForSlowPoles) {
  // g(x) = x - 3/2 + 2 e^-x - e^-2x / 2, reference values from 40-digit mpmath.
  const std::pair<double, double> ref[] = {
      {1e-6, 3.33333083333449999958341e-19}, {1e-3, 3.330834499583456317963347e-10},
      {0.1, 0.0003094595329282169935303646}, {0.5, 0.02912159883954568640983718},
      {0.999, 0.1676918969002309951983573},  {1.0, 0.1680912407245782972440478},
      {3.0, 1.598334760647394706747162}};
  for (const auto& [x, g] : ref) EXPECT_NEAR(gauss_markov_g(x) / g, 1.0, 4e-15) << x;
}

// Route 1 against route 2 (eq. 4 from the PSD) at 1e-6 relative, for each term and mixes,
// tau from one sample to 10^4 s.
TEST(Theory, ClosedFormsAgreeWithEq4FromThePsd) {
  const double tau0 = 0.005;
  std::vector<NoiseModel> models;
  NoiseModel m;
  m.n_unit_sqrt_s = 8.9e-4;
  models.push_back(m);
  m = {};
  m.k_unit_per_sqrt_s = 1.5e-5;
  models.push_back(m);
  m = {};
  m.gm_sigma_unit = 1e-3;
  m.gm_time_s = 3.0;
  models.push_back(m);
  m = {};
  m.gm_sigma_unit = 1e-3;
  m.gm_time_s = 1e-4;  // faster than a sample
  models.push_back(m);
  m = {};
  m.b_unit = 5.9e-4;
  m.flicker_tau_min_s = tau0;
  m.flicker_tau_max_s = 21600.0;
  models.push_back(m);
  m = {};
  m.sine_amplitude_unit = 0.01;
  m.sine_frequency_hz = 1.3;
  models.push_back(m);
  models.push_back(tg100_gyro1());
  m = tg100_gyro1();
  m.gm_sigma_unit = 2e-4;
  m.gm_time_s = 50.0;
  m.sine_amplitude_unit = 1e-3;
  m.sine_frequency_hz = 0.05;
  models.push_back(m);
  for (std::size_t i = 0; i < models.size(); ++i) {
    for (const double tau : log_grid(tau0, 1e4, 3)) {
      const double closed = allan_variance(models[i], tau);
      const double eq4 = allan_variance_eq4(models[i], tau0, tau);
      EXPECT_NEAR(eq4 / closed, 1.0, 1e-6) << "model " << i << " tau " << tau;
    }
  }
}

TEST(Theory, Eq4OfQuantizationIsExactAtEveryAveragingFactor) {
  NoiseModel m;
  m.q_unit_s = 1e-7;
  const double tau0 = 0.005;
  for (const int mf : {1, 2, 3, 7, 64, 1000}) {
    const double tau = mf * tau0;
    EXPECT_NEAR(allan_variance_eq4(m, tau0, tau) / allan_variance(m, tau), 1.0, 1e-9) << mf;
  }
}

TEST(Theory, Eq4OfIdealFlickerIsTheFloor) {
  NoiseModel m;
  m.b_unit = 2.0;
  for (const double tau : {1e-3, 1.0, 1e5}) {
    EXPECT_NEAR(allan_variance_eq4(m, 0.01, tau, FlickerForm::ideal) / nominal_allan_variance(m, tau), 1.0, 1e-6);
  }
}

TEST(Theory, RampHasNoEq4AndFlickerNeedsItsRange) {
  NoiseModel r;
  r.r_unit_per_s = 1e-3;
  EXPECT_THROW(allan_variance_eq4(r, 0.01, 1.0), imunoise::InputError);
  NoiseModel b;
  b.b_unit = 1.0;
  EXPECT_THROW(allan_variance(b, 1.0), imunoise::InputError);
  EXPECT_NO_THROW(allan_variance(b, 1.0, FlickerForm::ideal));
  EXPECT_THROW(allan_variance(b, -1.0, FlickerForm::ideal), imunoise::InputError);
}

TEST(Theory, PsdLevels) {
  NoiseModel m;
  m.n_unit_sqrt_s = 3.0;
  EXPECT_DOUBLE_EQ(psd(m, 0.01, 7.0), 9.0);
  m = {};
  m.k_unit_per_sqrt_s = 2.0;
  EXPECT_DOUBLE_EQ(psd(m, 0.01, 1.0 / (2 * std::numbers::pi)), 4.0);
  m = {};
  m.b_unit = 1.0;
  EXPECT_DOUBLE_EQ(psd(m, 0.01, 1.0 / (2 * std::numbers::pi), FlickerForm::ideal), 1.0);
  m.flicker_tau_min_s = 0.01;
  m.flicker_tau_max_s = 1e4;
  // The bank follows 1/f well inside its range (the Allan floor is the sharper statement).
  for (const double f : {1e-3, 1e-2, 0.1, 1.0}) {
    EXPECT_NEAR(psd(m, 0.01, f) / psd(m, 0.01, f, FlickerForm::ideal), 1.0, 0.03) << f;
  }
  m = {};
  m.q_unit_s = 1.0;
  EXPECT_DOUBLE_EQ(psd(m, 0.01, 60.0), 0.0);  // above Nyquist
}

// The stated accuracy of the flicker floor: |sigma_bank / (0.6643 B) - 1| <= 1e-3 over the whole
// stated range, for ranges of 1 to 12 decades at various places, 40 points per decade.
TEST(Flicker, FloorWithinStatedToleranceOverStatedRange) {
  struct Range {
    double lo, hi;
  };
  for (const Range r : {Range{0.005, 21600.0}, Range{1e-3, 1e-2}, Range{0.01, 1e10}, Range{1.0, 1e5},
                        Range{3e-6, 3e6}, Range{0.005, 0.05}}) {
    const FlickerBank bank = design_flicker_bank(1.0, r.lo, r.hi);
    double worst = 0.0;
    for (const double tau : log_grid(r.lo, r.hi, 40)) {
      const double dev = std::sqrt(flicker_bank_allan_variance(bank, tau));
      worst = std::max(worst, std::fabs(dev / kFlickerFloorPerB - 1.0));
    }
    EXPECT_LE(worst, kFlickerFloorTolerance) << r.lo << ".." << r.hi;
    // 1.5 poles per decade plus margins.
    const double decades = std::log10(r.hi * kFlickerHighMargin * kFlickerLowMargin / r.lo);
    EXPECT_LE(static_cast<double>(bank.poles.size()), decades * kFlickerPolesPerDecade + 2.0);
  }
}

TEST(Flicker, BankScalesWithB) {
  const FlickerBank a = design_flicker_bank(1.0, 0.01, 100.0);
  const FlickerBank b = design_flicker_bank(3.0, 0.01, 100.0);
  ASSERT_EQ(a.poles.size(), b.poles.size());
  EXPECT_NEAR(flicker_bank_allan_variance(b, 1.0) / flicker_bank_allan_variance(a, 1.0), 9.0, 1e-12);
  EXPECT_TRUE(design_flicker_bank(0.0, 0.01, 100.0).poles.empty());
}

TEST(Flicker, RangesItCannotHonour) {
  EXPECT_THROW(design_flicker_bank(1.0, 1.0, 1.0), imunoise::InputError);
  EXPECT_THROW(design_flicker_bank(1.0, 1.0, 0.5), imunoise::InputError);
  EXPECT_THROW(design_flicker_bank(1.0, 0.0, 10.0), imunoise::InputError);
  EXPECT_THROW(design_flicker_bank(1.0, 1e-3, 1e10), imunoise::InputError);  // 13 decades
  EXPECT_THROW(design_flicker_bank(-1.0, 1e-3, 1.0), imunoise::InputError);
  EXPECT_THROW(design_flicker_bank(NAN, 1e-3, 1.0), imunoise::InputError);
}
