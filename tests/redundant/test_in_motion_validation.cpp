// Validation of the in-motion analysis on simulated units with known truth (the project's
// simulator): different noise per sensor, a common rotation to 200 deg/s on every axis through
// the geometry, each sensor's N and K recovered from its in-motion curve by the noise-model fit.
//
// Record length: 4000 s at 100 Hz. With K ~ 1e-3 deg/s/sqrt(s) and N ~ 1e-3 deg/sqrt(s) the
// white and random-walk terms cross at tau = sqrt(3) N / K ~ 2 s, so N is fitted over 0.01-1 s
// (in-motion EDF in the thousands: N to ~1 %) and K over 4-1000 s, where the in-motion EDF of
// each a_i falls from ~100 to a few (it also carries the other sensors' noise). Measured over
// seeds 1-20 (15 sensors a seed, both geometries): N outside 5 % or K outside 30 % for 7 of 300
// sensor fits at 2000 s, 3 of 300 at 4000 s, 2 of 300 at 8000 s; 4000 s keeps the test near a
// second. Most misses are the fit's model selection dropping a term at the noisiest long taus.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/redundant/in_motion.hpp"
#include "imunoise/study/in_motion.hpp"
#include "redundant/redundant_test_support.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;
using namespace imunoise::redundant_test;

std::array<double, 3> tumbling(double t) {
  const double w = 200.0 * kDeg;
  return {w * std::sin(2 * std::numbers::pi * 0.5 * t), w * std::sin(2 * std::numbers::pi * 0.31 * t + 1.0),
          w * std::sin(2 * std::numbers::pi * 0.17 * t + 2.0)};
}

constexpr double kDuration_s = 4000.0;


Geometry co_aligned_triads() {
  std::vector<Axis> axes;
  for (int c = 0; c < 3; ++c) {
    axes.push_back({1, 0, 0});
    axes.push_back({0, 1, 0});
    axes.push_back({0, 0, 1});
  }
  return geometry_from_axes("three co-aligned triads", axes);
}

std::vector<sim::NoiseModel> varied_models(std::size_t n) {
  const double n_scale[9] = {1.0, 1.3, 1.6, 0.8, 1.1, 1.4, 0.9, 1.2, 1.5};
  const double k_scale[9] = {1.0, 0.6, 1.4, 0.8, 1.2, 0.7, 1.1, 0.9, 1.3};
  std::vector<sim::NoiseModel> m(n);
  for (std::size_t i = 0; i < n; ++i) {
    m[i].n_unit_sqrt_s = 1e-3 * n_scale[i];
    m[i].k_unit_per_sqrt_s = 1e-3 * k_scale[i];
  }
  return m;
}

void expect_recovered(const Geometry& g, std::uint64_t seed) {
  const auto models = varied_models(g.size());
  const double rate = 100.0;
  auto recs = as_records(simulate_unit(g, models, rate, kDuration_s, seed, tumbling), rate);
  InMotionOptions o;
  o.require_per_sensor = true;
  const auto unit = study::analyze_in_motion(g, std::move(recs), o, fit::FitOptions{});
  ASSERT_EQ(unit.sensors.size(), g.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    const auto& s = unit.sensors[i];
    ASSERT_TRUE(s.identified);
    ASSERT_TRUE(s.fit.has_value()) << s.reason;
    const double n_true = models[i].n_unit_sqrt_s * kDeg;
    const double k_true = models[i].k_unit_per_sqrt_s * kDeg;
    const double n_fit = s.fit->coefficients.random_walk.value;
    const double k_fit = s.fit->coefficients.rate_random_walk.value;
    std::printf("%s sensor %zu: fitted / true N %.4f, K %.4f\n", g.name.c_str(), i + 1, n_fit / n_true, k_fit / k_true);
    EXPECT_NEAR(n_fit / n_true, 1.0, 0.05) << g.name << " sensor " << i + 1;
    EXPECT_NEAR(k_fit / k_true, 1.0, 0.30) << g.name << " sensor " << i + 1;
  }
}

TEST(RedundantInMotionValidation, ThreeCoAlignedTriadsUnderMotionGiveEachSensorsNoise) {
  expect_recovered(co_aligned_triads(), 101);
}

TEST(RedundantInMotionValidation, DodecahedralSixGyroUnitUnderMotionGivesEachSensorsNoise) {
  expect_recovered(make_geometry("dodeca"), 202);
}

TEST(RedundantInMotionValidation, TetrahedronMeanLevelIsRightAndPerSensorIsRefused) {
  const Geometry g = make_geometry("tetra");
  const auto models = varied_models(4);
  auto recs = as_records(simulate_unit(g, models, 100.0, 2000.0, 303, tumbling), 100.0);
  InMotionOptions o;
  auto unit = study::analyze_in_motion(g, recs, o, fit::FitOptions{});
  for (const auto& s : unit.sensors) {
    EXPECT_FALSE(s.identified);
    EXPECT_FALSE(s.fit.has_value());
    EXPECT_NE(s.reason.find("fewer equations than sensors"), std::string::npos) << s.reason;
  }
  // The mean level against the truth sum_i a_i / 4 with a_i = N_i^2 / tau + K_i^2 tau / 3.
  std::size_t covered = 0;
  for (const auto& p : unit.result.common) {
    double truth = 0;
    for (const auto& m : models) {
      const double n = m.n_unit_sqrt_s * kDeg;
      const double k = m.k_unit_per_sqrt_s * kDeg;
      truth += (n * n / p.tau_s + k * k * p.tau_s / 3) / 4;
    }
    const double dev = std::sqrt(truth);
    EXPECT_NEAR(p.dev / dev, 1.0, 4 / std::sqrt(2 * p.edf)) << p.tau_s;
    covered += (p.ci_low <= dev && dev <= p.ci_high) ? 1 : 0;
  }
  EXPECT_GE(covered, unit.result.common.size() / 2);
  InMotionOptions strict;
  strict.require_per_sensor = true;
  try {
    (void)study::analyze_in_motion(g, recs, strict, fit::FitOptions{});
    FAIL() << "per-sensor curves of the tetrahedron accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("4 sensors"), std::string::npos) << e.what();
  }
}

TEST(RedundantInMotionValidation, UnitChecksNameTheFiles) {
  const Geometry g = make_geometry("dodeca");
  auto recs = as_records(simulate_unit(g, varied_models(6), 100.0, 20.0, 1, tumbling), 100.0);
  auto short_one = recs;
  short_one[2].rate_si.pop_back();
  try {
    (void)study::analyze_in_motion(g, short_one, {}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor3 has 1999 samples"), std::string::npos) << e.what();
  }
  auto other_rate = recs;
  other_rate[4].rate_hz = 200.0;
  EXPECT_THROW((void)study::analyze_in_motion(g, other_rate, {}, {}), InputError);
  auto fewer = recs;
  fewer.pop_back();
  try {
    (void)study::analyze_in_motion(g, fewer, {}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("5 recordings for the 6 sensors"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// Monte Carlo coverage of the per-sensor 95 % intervals (white and random-walk noise, whose
// Allan variance N^2 / tau + K^2 tau / 3 is the truth), over every tau of the octave grid.
double coverage(const Geometry& g, int runs, double duration_s, std::vector<double>* per_tau) {
  const auto models = varied_models(g.size());
  InMotionOptions o;
  o.ci_level = 0.95;
  std::size_t hit = 0;
  std::size_t total = 0;
  std::vector<std::size_t> tau_hit;
  std::size_t tau_runs = 0;
  for (int run = 0; run < runs; ++run) {
    const auto rec = simulate_unit(g, models, 100.0, duration_s, 5000 + static_cast<std::uint64_t>(run), tumbling);
    const auto r = in_motion_noise(g, spans_of(rec), 100.0, o);
    tau_hit.resize(r.points.size(), 0);
    ++tau_runs;
    for (std::size_t i = 0; i < g.size(); ++i) {
      const double n = models[i].n_unit_sqrt_s * kDeg;
      const double k = models[i].k_unit_per_sqrt_s * kDeg;
      for (std::size_t q = 0; q < r.sensors[i].size(); ++q) {
        const auto& p = r.sensors[i][q];
        const double truth = std::sqrt(n * n / p.tau_s + k * k * p.tau_s / 3);
        const bool in = p.ci_low <= truth && truth <= p.ci_high;
        hit += in ? 1 : 0;
        tau_hit[q] += in ? 1 : 0;
        ++total;
      }
    }
  }
  if (per_tau != nullptr) {
    per_tau->clear();
    for (auto h : tau_hit) per_tau->push_back(static_cast<double>(h) / static_cast<double>(tau_runs * g.size()));
  }
  return static_cast<double>(hit) / static_cast<double>(total);
}

TEST(SlowInMotionCoverage, PerSensorIntervalsCoverTheTruth) {
  for (const char* name : {"dodeca", "triads"}) {
    const Geometry g = std::string(name) == "dodeca" ? make_geometry("dodeca") : co_aligned_triads();
    std::vector<double> per_tau;
    const double c = coverage(g, 200, 400.0, &per_tau);
    std::printf("%s: 95 %% intervals cover %.3f; per tau:", name, c);
    for (double x : per_tau) std::printf(" %.2f", x);
    std::printf("\n");
    EXPECT_GE(c, 0.90) << name;
    EXPECT_LE(c, 0.98) << name;
  }
}

}  // namespace

namespace {

// A dodecahedral unit whose sensor 1 has a 1000 ppm scale-factor error and sensor 2 a 1 mrad
// misalignment, white noise only, under the tumble (and at rest): the leaked motion dominates
// the parity unless removed.
struct LeakyUnit {
  Geometry g = make_geometry("dodeca");
  std::vector<sim::NoiseModel> models = varied_models(6);
  std::vector<std::array<double, 3>> d;  // d_i: (h_i + d_i) . w is measured
  std::vector<std::vector<double>> rec;
};

LeakyUnit leaky_unit(bool moving) {
  LeakyUnit u;
  for (auto& m : u.models) m.k_unit_per_sqrt_s = 0.0;
  u.d.assign(6, {0.0, 0.0, 0.0});
  for (int a = 0; a < 3; ++a) u.d[0][a] = 1e-3 * u.g.axes[0][a];
  // A unit vector perpendicular to h_2: (h_2 x z) normalised.
  const auto& h2 = u.g.axes[1];
  std::array<double, 3> perp{h2[1], -h2[0], 0.0};
  const double norm = std::hypot(perp[0], perp[1]);
  for (int a = 0; a < 3; ++a) u.d[1][a] = 1e-3 * perp[a] / norm;
  auto still = [](double) { return std::array<double, 3>{0.0, 0.0, 0.0}; };
  u.rec = simulate_unit(u.g, u.models, 100.0, 600.0, 909, still);
  if (moving) {
    for (std::size_t t = 0; t < u.rec[0].size(); ++t) {
      const auto w = tumbling((static_cast<double>(t) + 0.5) / 100.0);
      for (std::size_t i = 0; i < 6; ++i) {
        double s = 0;
        for (int a = 0; a < 3; ++a) s += (u.g.axes[i][a] + u.d[i][a]) * w[a];
        u.rec[i][t] += s;
      }
    }
  }
  return u;
}

TEST(RedundantInMotionValidation, MotionLeakageIsEstimatedAndRemoved) {
  const LeakyUnit u = leaky_unit(true);
  InMotionOptions keep;
  keep.remove_leakage = false;
  const auto raw = in_motion_noise(u.g, spans_of(u.rec), 100.0, keep);
  const auto clean = in_motion_noise(u.g, spans_of(u.rec), 100.0);
  ASSERT_TRUE(clean.leakage.removed);
  EXPECT_FALSE(raw.leakage.removed);
  std::size_t q1 = 0;  // tau = 1.28 s
  while (raw.points[q1].tau_s < 1.0) ++q1;
  for (std::size_t i = 0; i < 6; ++i) {
    const double n = u.models[i].n_unit_sqrt_s * kDeg;
    const double truth = n / std::sqrt(raw.points[q1].tau_s);
    // Without removal the leaked motion swamps the noise of the sensors it reaches.
    if (i < 2) {
      EXPECT_GT(raw.sensors[i][q1].dev / truth, 3.0) << i;
    }
    std::printf("sensor %zu at tau %.2f s: adev / truth %.2f without removal, %.3f with; scale factor %.1f ppm, "
                "misalignment %.3f mrad (relative)\n", i + 1, raw.points[q1].tau_s, raw.sensors[i][q1].dev / truth,
                clean.sensors[i][q1].dev / truth, clean.leakage.scale_factor_ppm[i], clean.leakage.misalignment_mrad[i]);
    // Removed: each sensor's white noise at every tau up to 20 s within 4 standard errors.
    for (std::size_t q = 0; q < clean.points.size() && clean.points[q].tau_s <= 20.0; ++q) {
      const auto& p = clean.sensors[i][q];
      const double t = n / std::sqrt(p.tau_s);
      EXPECT_NEAR(p.dev / t, 1.0, 4.0 / std::sqrt(2.0 * p.edf)) << "sensor " << i + 1 << " tau " << p.tau_s;
    }
  }
  // The coefficients are the visible part B = V D; the per-sensor figures those of P D.
  const Matrix v = parity_of(measurement_matrix(u.g));
  for (std::size_t j = 0; j < v.rows; ++j) {
    for (std::size_t a = 0; a < 3; ++a) {
      double b = 0;
      for (std::size_t i = 0; i < 6; ++i) b += v(j, i) * u.d[i][a];
      EXPECT_NEAR(clean.leakage.coefficients(j, a), b, 2e-6) << j << "," << a;
    }
  }
  for (std::size_t i = 0; i < 6; ++i) {
    std::array<double, 3> pd{0, 0, 0};
    for (std::size_t l = 0; l < 6; ++l) {
      double pil = 0;
      for (std::size_t j = 0; j < v.rows; ++j) pil += v(j, i) * v(j, l);
      for (int a = 0; a < 3; ++a) pd[a] += pil * u.d[l][a];
    }
    const auto& h = u.g.axes[i];
    const double sf = 1e6 * (pd[0] * h[0] + pd[1] * h[1] + pd[2] * h[2]);
    EXPECT_NEAR(clean.leakage.scale_factor_ppm[i], sf, 3.0) << i;
  }
  // The dodecahedron's P_ii = 1/2: sensor 1's 1000 ppm shows as 500 on it.
  EXPECT_NEAR(clean.leakage.scale_factor_ppm[0], 500.0, 5.0);
  EXPECT_GT(clean.leakage.misalignment_mrad[1], 0.3);
}

TEST(RedundantInMotionValidation, LeakageRemovalAtRestLeavesTheNoiseAlone) {
  // No motion: the regressor is the fused noise, uncorrelated with the parity under the noise
  // weighting, so removal must not eat the noise.
  const LeakyUnit u = leaky_unit(false);
  InMotionOptions keep;
  keep.remove_leakage = false;
  const auto raw = in_motion_noise(u.g, spans_of(u.rec), 100.0, keep);
  const auto clean = in_motion_noise(u.g, spans_of(u.rec), 100.0);
  for (std::size_t i = 0; i < 6; ++i) {
    for (std::size_t q = 0; q < 8; ++q) {
      EXPECT_NEAR(clean.sensors[i][q].dev / raw.sensors[i][q].dev, 1.0, 0.01) << i << " " << q;
    }
  }
  // No motion: nothing to calibrate against; the coefficients are noise over noise, whatever
  // their size, and the test is that the noise curves above did not move.
}

}  // namespace

namespace {

TEST(RedundantInMotionValidation, CoefficientRatioCombinesLogNormalIntervals) {
  Coefficient a, b;
  a.identified = b.identified = true;
  a.value = 3.0;
  a.ci_low = 3.0 / 1.2;
  a.ci_high = 3.0 * 1.2;
  b.value = 2.0;
  b.ci_low = 2.0 / 1.1;
  b.ci_high = 2.0 * 1.1;
  const auto r = study::coefficient_ratio(a, b, 0.95);
  ASSERT_TRUE(r.available);
  EXPECT_DOUBLE_EQ(r.ratio, 1.5);
  const double s = std::hypot(std::log(1.2), std::log(1.1));  // the half-widths of ln add in quadrature
  EXPECT_NEAR(r.ci_high / r.ratio, std::exp(s), 1e-12);
  EXPECT_NEAR(r.ratio / r.ci_low, std::exp(s), 1e-12);
  b.identified = false;
  EXPECT_FALSE(study::coefficient_ratio(a, b, 0.95).available);
  b.identified = true;
  b.ci_low = 0.0;
  EXPECT_FALSE(study::coefficient_ratio(a, b, 0.95).available);
}

TEST(RedundantInMotionValidation, InflationAgainstStaticRecordings) {
  // The sensors are 1.5 times noisier (N) in motion than at rest; K the same.
  const Geometry g = make_geometry("dodeca");
  auto moving = varied_models(6);
  auto still = moving;
  for (auto& m : moving) m.n_unit_sqrt_s *= 1.5;
  auto unit = study::analyze_in_motion(g, as_records(simulate_unit(g, moving, 100.0, kDuration_s, 404, tumbling), 100.0),
                                       {}, fit::FitOptions{});
  std::vector<Record> statics;
  for (std::size_t i = 0; i < 6; ++i) {
    Record r;
    r.name = r.source = "static" + std::to_string(i + 1);
    r.rate_hz = 100.0;
    r.rate_unit = Unit{"rad/s", Quantity::angular_rate, 1.0};
    r.unit_given = true;
    auto x = sim::simulate(still[i], 100.0, static_cast<std::size_t>(kDuration_s * 100), 505, i);
    for (auto& v : x) v *= kDeg;
    r.n_samples = x.size();
    r.phase_si = phase_from_rate(x, 0.01, compensated_mean(x));
    statics.push_back(std::move(r));
  }
  auto fewer = statics;
  fewer.pop_back();
  EXPECT_THROW(study::compare_with_static(unit, fewer, {}), InputError);
  study::compare_with_static(unit, statics, fit::FitOptions{});
  for (const auto& s : unit.sensors) {
    ASSERT_EQ(s.inflation.size(), 3u);
    const auto& n = s.inflation[0].second;
    ASSERT_TRUE(n.available) << n.reason;
    std::printf("%s: N in motion / at rest %.3f [%.3f, %.3f]\n", s.record.source.c_str(), n.ratio, n.ci_low, n.ci_high);
    EXPECT_NEAR(n.ratio, 1.5, 0.075);
    EXPECT_LT(n.ci_low, 1.5);
    EXPECT_GT(n.ci_high, 1.5);
    const auto& k = s.inflation[2].second;
    ASSERT_TRUE(k.available) << k.reason;
    EXPECT_NEAR(k.ratio, 1.0, 0.45);
  }
  const auto doc = study::in_motion_json(unit, fit::FitOptions{});
  EXPECT_TRUE(doc["sensors"][0]["inflation"]["N"]["ratio"].is_number());
  EXPECT_TRUE(doc["sensors"][0]["static_fit"]["terms"]["N"]["value"].is_number());
}

}  // namespace
