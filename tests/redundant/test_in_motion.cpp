// The in-motion estimator (redundant/in_motion.hpp): its parts against independent forms (the
// project's oadev, the classical three-cornered hat, brute-force least squares) and what each
// geometry can identify.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/redundant/in_motion.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "redundant/redundant_test_support.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;
using namespace imunoise::redundant_test;

// Fast common motion on all axes, to 200 deg/s: it must cancel in the parity.
std::array<double, 3> tumbling(double t) {
  const double w = 200.0 * kDeg;
  return {w * std::sin(2 * std::numbers::pi * 0.5 * t), w * std::sin(2 * std::numbers::pi * 0.31 * t + 1.0),
          w * std::sin(2 * std::numbers::pi * 0.17 * t + 2.0)};
}

std::vector<double> oavar_of(std::span<const double> rate, double rate_hz, std::span<const std::size_t> m) {
  const auto x = phase_from_rate(rate, 1.0 / rate_hz, compensated_mean(rate));
  std::vector<double> out;
  for (const auto& p : oadev(x, 1.0 / rate_hz, m)) out.push_back(p.dev * p.dev);
  return out;
}

TEST(RedundantInMotion, AllanCovarianceDiagonalIsTheOverlappingAllanVariance) {
  sim::NoiseModel a;
  a.n_unit_sqrt_s = 1e-3;
  a.k_unit_per_sqrt_s = 1e-4;
  const auto x = sim::simulate(a, 100.0, 5000, 3, 0);
  const auto y = sim::simulate(a, 100.0, 5000, 3, 1);
  const auto px = phase_from_rate(x, 0.01, compensated_mean(x));
  const auto py = phase_from_rate(y, 0.01, compensated_mean(y));
  std::vector<double> sum(x.size());
  for (std::size_t t = 0; t < x.size(); ++t) sum[t] = x[t] + y[t];
  const std::vector<std::span<const double>> ph{px, py};
  for (std::size_t m : {1u, 7u, 100u, 2000u}) {
    const std::vector<std::size_t> ms{m};
    const Matrix c = allan_covariance(ph, 0.01, m);
    const double vx = oavar_of(x, 100.0, ms)[0];
    const double vy = oavar_of(y, 100.0, ms)[0];
    const double vs = oavar_of(sum, 100.0, ms)[0];
    EXPECT_NEAR(c(0, 0), vx, 1e-10 * vx) << m;
    EXPECT_NEAR(c(1, 1), vy, 1e-10 * vy) << m;
    // Bilinearity: avar(x + y) = avar(x) + avar(y) + 2 cov(x, y).
    EXPECT_NEAR(c(0, 0) + c(1, 1) + 2 * c(0, 1), vs, 1e-9 * vs) << m;
    EXPECT_EQ(c(0, 1), c(1, 0));
  }
  EXPECT_THROW(allan_covariance(ph, 0.01, 2501), InputError);
}

TEST(RedundantInMotion, ReproducesTheClassicalThreeCorneredHatExactly) {
  // Three co-aligned sensors (H = (1, 1, 1)^T), different white and random-walk noise, a common
  // fast rotation. Gray & Allan 1974: a_1 = (s12 + s13 - s23) / 2, s_ij = avar(m_i - m_j).
  Matrix h(3, 1);
  for (std::size_t i = 0; i < 3; ++i) h(i, 0) = 1.0;
  std::vector<std::vector<double>> m(3);
  const double n_deg[3] = {1e-3, 2e-3, 1.5e-3};
  for (std::size_t i = 0; i < 3; ++i) {
    sim::NoiseModel model;
    model.n_unit_sqrt_s = n_deg[i];
    model.k_unit_per_sqrt_s = 1e-4 * static_cast<double>(i + 1);
    m[i] = sim::simulate(model, 100.0, 60000, 11, i);
    for (std::size_t t = 0; t < m[i].size(); ++t) {
      m[i][t] = m[i][t] * kDeg + tumbling((static_cast<double>(t) + 0.5) / 100.0)[0];
    }
  }
  InMotionOptions o;
  o.remove_leakage = false;  // the classical hat takes the differences as they are
  const InMotionResult r = in_motion_noise(h, spans_of(m), 100.0, o);
  ASSERT_TRUE(r.identifiability.per_sensor);
  EXPECT_EQ(r.identifiability.parity_channels, 2u);
  EXPECT_EQ(r.identifiability.equations, 3u);
  auto diff = [&](std::size_t i, std::size_t j) {
    std::vector<double> d(m[i].size());
    for (std::size_t t = 0; t < d.size(); ++t) d[t] = m[i][t] - m[j][t];
    return d;
  };
  std::vector<std::size_t> factors;
  for (const auto& p : r.points) factors.push_back(p.m);
  ASSERT_GT(factors.size(), 10u);
  const auto s12 = oavar_of(diff(0, 1), 100.0, factors);
  const auto s13 = oavar_of(diff(0, 2), 100.0, factors);
  const auto s23 = oavar_of(diff(1, 2), 100.0, factors);
  std::size_t compared = 0;
  for (std::size_t q = 0; q < factors.size(); ++q) {
    const double a1 = (s12[q] + s13[q] - s23[q]) / 2;
    const double a2 = (s12[q] + s23[q] - s13[q]) / 2;
    const double a3 = (s13[q] + s23[q] - s12[q]) / 2;
    if (a1 <= 0 || a2 <= 0 || a3 <= 0) continue;  // the classical hat goes negative; NNLS stops at 0
    ++compared;
    const auto& e = r.points[q].estimate;
    EXPECT_NEAR(e[0], a1, 1e-9 * (a1 + a2 + a3)) << factors[q];
    EXPECT_NEAR(e[1], a2, 1e-9 * (a1 + a2 + a3)) << factors[q];
    EXPECT_NEAR(e[2], a3, 1e-9 * (a1 + a2 + a3)) << factors[q];
    EXPECT_DOUBLE_EQ(r.sensors[0][q].dev, std::sqrt(e[0]));
  }
  EXPECT_GT(compared, 8u);
}

TEST(RedundantInMotion, IdentifiabilityPerGeometry) {
  auto id_of = [](const Geometry& g) { return identifiability(parity_of(measurement_matrix(g))); };
  const auto tetra = id_of(make_geometry("tetra"));
  EXPECT_EQ(tetra.parity_channels, 1u);
  EXPECT_EQ(tetra.equations, 1u);
  EXPECT_EQ(tetra.rank, 1u);
  EXPECT_FALSE(tetra.per_sensor);
  EXPECT_NE(tetra.reason.find("fewer equations than sensors"), std::string::npos) << tetra.reason;
  ASSERT_EQ(tetra.common_weights.size(), 4u);
  for (double w : tetra.common_weights) EXPECT_NEAR(w, 0.25, 1e-12);  // the plain mean of the four

  const auto three_one = id_of(make_geometry("3+1"));
  EXPECT_EQ(three_one.rank, 1u);
  EXPECT_FALSE(three_one.per_sensor);
  EXPECT_EQ(id_of(make_geometry("cone:8:40")).rank, 8u);
  const auto five = id_of(make_geometry("cone:5:54.7356"));
  EXPECT_EQ(five.rank, 3u);
  EXPECT_EQ(five.equations, 3u);
  EXPECT_FALSE(five.per_sensor);

  // The symmetric six-axis cone: six equations but rank 5 at every half-angle; what is lost is
  // the difference between its interleaved triads.
  for (const char* spec : {"cone:6:54.7356", "cone:6:30", "cone:6:70"}) {
    const auto six = id_of(make_geometry(spec));
    EXPECT_EQ(six.parity_channels, 3u);
    EXPECT_EQ(six.equations, 6u);
    EXPECT_EQ(six.rank, 5u) << spec;
    EXPECT_FALSE(six.per_sensor);
    EXPECT_NE(six.reason.find("only 5 combinations"), std::string::npos) << six.reason;
    ASSERT_EQ(six.unobservable.size(), 1u);
    for (std::size_t i = 0; i < 6; ++i) {
      EXPECT_NEAR(six.unobservable[0][i], (i % 2 ? -1.0 : 1.0) / std::sqrt(6.0), 1e-9) << spec;
    }
  }
  // The dodecahedral six-gyro unit and seven on a cone: every sensor.
  const auto dodeca = id_of(make_geometry("dodeca"));
  EXPECT_EQ(dodeca.rank, 6u);
  EXPECT_TRUE(dodeca.per_sensor);
  EXPECT_TRUE(dodeca.unobservable.empty());
  EXPECT_TRUE(id_of(make_geometry("cone:7:54.7356")).per_sensor);

  // Three co-aligned triads: nine rows, six parity channels, 21 equations.
  std::vector<Axis> nine;
  for (int c = 0; c < 3; ++c) {
    nine.push_back({1, 0, 0});
    nine.push_back({0, 1, 0});
    nine.push_back({0, 0, 1});
  }
  const auto triads = id_of(geometry_from_axes("triads", nine));
  EXPECT_EQ(triads.parity_channels, 6u);
  EXPECT_EQ(triads.equations, 21u);
  EXPECT_TRUE(triads.per_sensor);
  // Two co-aligned triads: each axis a two-cornered hat, which cannot separate its sensors.
  nine.resize(6);
  const auto pairs = id_of(geometry_from_axes("two triads", nine));
  EXPECT_EQ(pairs.equations, 6u);
  EXPECT_EQ(pairs.rank, 3u);
  EXPECT_FALSE(pairs.per_sensor);
  EXPECT_NE(pairs.reason.find("only 3 combinations"), std::string::npos) << pairs.reason;
  for (double w : pairs.common_weights) EXPECT_NEAR(w, 1.0 / 6.0, 1e-12);
}

TEST(RedundantInMotion, NonNegativeLeastSquaresMatchesEveryActiveSet) {
  // Brute force: the best non-negative solution is the best feasible least-squares solution
  // over all 2^n supports.
  Matrix a(6, 4);
  const double vals[24] = {1, 0.2, -0.3, 0.5, 0.1, 1, 0.4, -0.2, -0.5, 0.3, 1, 0.1,
                           0.2, 0.1, -0.4, 1, 0.7, -0.6, 0.2, 0.3, -0.1, 0.5, 0.8, -0.9};
  std::copy(std::begin(vals), std::end(vals), a.values.begin());
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> b(6);
    for (std::size_t i = 0; i < 6; ++i) b[i] = std::sin(1.7 * static_cast<double>(i + 1) * (trial + 1)) * 2;
    const auto x = nonnegative_least_squares(a, b);
    auto cost = [&](const std::vector<double>& xx) {
      double c = 0;
      for (std::size_t r = 0; r < 6; ++r) {
        double s = -b[r];
        for (std::size_t j = 0; j < 4; ++j) s += a(r, j) * xx[j];
        c += s * s;
      }
      return c;
    };
    double best = cost(std::vector<double>(4, 0.0));
    for (int mask = 1; mask < 16; ++mask) {
      // Normal equations on the support, by Gaussian elimination (independent of the solver).
      std::vector<std::size_t> s;
      for (std::size_t j = 0; j < 4; ++j) {
        if (mask & (1 << j)) s.push_back(j);
      }
      const std::size_t q = s.size();
      std::vector<std::vector<double>> ne(q, std::vector<double>(q + 1, 0.0));
      for (std::size_t u = 0; u < q; ++u) {
        for (std::size_t r = 0; r < 6; ++r) {
          for (std::size_t w = 0; w < q; ++w) ne[u][w] += a(r, s[u]) * a(r, s[w]);
          ne[u][q] += a(r, s[u]) * b[r];
        }
      }
      for (std::size_t p = 0; p < q; ++p) {
        for (std::size_t u = p + 1; u < q; ++u) {
          const double f = ne[u][p] / ne[p][p];
          for (std::size_t w = p; w <= q; ++w) ne[u][w] -= f * ne[p][w];
        }
      }
      std::vector<double> y(q);
      for (std::size_t p = q; p-- > 0;) {
        double v = ne[p][q];
        for (std::size_t w = p + 1; w < q; ++w) v -= ne[p][w] * y[w];
        y[p] = v / ne[p][p];
      }
      if (std::any_of(y.begin(), y.end(), [](double v) { return v < 0; })) continue;
      std::vector<double> xx(4, 0.0);
      for (std::size_t u = 0; u < q; ++u) xx[s[u]] = y[u];
      best = std::min(best, cost(xx));
    }
    for (double v : x) EXPECT_GE(v, 0.0);
    EXPECT_NEAR(cost(x), best, 1e-12 * std::max(1.0, best)) << trial;
  }
}

TEST(RedundantInMotion, TetrahedronGivesTheMeanLevelAndRefusesPerSensorCurves) {
  // The tetrahedron's one parity channel holds the mean of the four sensors' Allan variances
  // exactly (weights |v_i|^2 = 1/4), whatever their noise; no sensor has its own curve.
  const Geometry g = make_geometry("tetra");
  std::vector<sim::NoiseModel> models(4);
  const double n_deg[4] = {1e-3, 2e-3, 1.2e-3, 3e-3};
  for (std::size_t i = 0; i < 4; ++i) models[i].n_unit_sqrt_s = n_deg[i];
  const auto rec = simulate_unit(g, models, 100.0, 600.0, 21, tumbling);
  const InMotionResult r = in_motion_noise(g, spans_of(rec), 100.0);
  EXPECT_FALSE(r.identifiability.per_sensor);
  EXPECT_TRUE(r.sensors.empty());
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes[0].find("fewer equations than sensors"), std::string::npos);
  double mean_n2 = 0;
  for (double n : n_deg) mean_n2 += n * n * kDeg * kDeg / 4;
  for (const auto& p : r.common) {
    if (p.tau_s > 10.0) break;
    const double truth = std::sqrt(mean_n2 / p.tau_s);
    // Within 4 standard errors of the estimate (sd of a deviation ~ dev / sqrt(2 edf)).
    EXPECT_NEAR(p.dev, truth, 4 * truth / std::sqrt(2 * p.edf)) << p.tau_s;
    EXPECT_LT(p.ci_low, p.dev);
    EXPECT_GT(p.ci_high, p.dev);
  }
  InMotionOptions strict;
  strict.require_per_sensor = true;
  try {
    (void)in_motion_noise(g, spans_of(rec), 100.0, strict);
    FAIL() << "per-sensor curves of a tetrahedron accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fewer equations than sensors"), std::string::npos) << e.what();
  }
}

TEST(RedundantInMotion, RefusesBadInput) {
  const Geometry g = make_geometry("cone:6:54.7356");
  std::vector<std::vector<double>> rec(6, std::vector<double>(1000, 0.0));
  for (std::size_t i = 0; i < 6; ++i) {
    for (std::size_t t = 0; t < 1000; ++t) rec[i][t] = std::sin(0.1 * static_cast<double>(t * (i + 1)));
  }
  auto spans = spans_of(rec);
  EXPECT_THROW(in_motion_noise(g, std::span(spans).first(5), 100.0), InputError);
  rec[3].resize(999);
  spans = spans_of(rec);
  EXPECT_THROW(in_motion_noise(g, spans, 100.0), InputError);
  EXPECT_THROW(in_motion_noise(g, spans, 0.0), InputError);
  // Three sensors spanning three axes: no parity.
  Matrix h(3, 3);
  h(0, 0) = h(1, 1) = h(2, 2) = 1.0;
  std::vector<std::vector<double>> three(3, std::vector<double>(100, 0.1));
  EXPECT_THROW(in_motion_noise(h, spans_of(three), 100.0), InputError);
}

}  // namespace
