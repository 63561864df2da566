// The generator: reproducibility (chunks, threads, seeds, golden bits), additivity of terms,
// exact per-sample values of the deterministic terms, the output stage, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/sim/presets.hpp"
#include "imunoise/sim/rng.hpp"
#include "imunoise/sim/theory.hpp"

using namespace imunoise::sim;

namespace {

NoiseModel full_model() {
  NoiseModel m;
  m.q_unit_s = 1e-5;
  m.n_unit_sqrt_s = 8.9e-4;
  m.b_unit = 5.9e-4;
  m.k_unit_per_sqrt_s = 1.5e-5;
  m.r_unit_per_s = 1e-6;
  m.gm_sigma_unit = 2e-3;
  m.gm_time_s = 0.7;
  m.sine_amplitude_unit = 3e-3;
  m.sine_frequency_hz = 1.7;
  m.sine_phase_rad = 0.4;
  m.bias_unit = -0.25;
  return m;
}

std::uint64_t bits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

// FNV-1a over the bit patterns: a compact fingerprint of a sample sequence.
std::uint64_t fingerprint(const std::vector<double>& v) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const double x : v) {
    std::uint64_t u = bits(x);
    for (int i = 0; i < 8; ++i) {
      h ^= (u & 0xffU);
      h *= 0x100000001b3ULL;
      u >>= 8;
    }
  }
  return h;
}

bool identical(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (bits(a[i]) != bits(b[i])) return false;
  }
  return true;
}

}  // namespace

TEST(Generator, SameSeedSameBitsDifferentSeedDifferentBits) {
  const auto a = simulate(full_model(), 200.0, 5000, 17);
  const auto b = simulate(full_model(), 200.0, 5000, 17);
  const auto c = simulate(full_model(), 200.0, 5000, 18);
  EXPECT_TRUE(identical(a, b));
  EXPECT_FALSE(identical(a, c));
  const auto other_channel = simulate(full_model(), 200.0, 5000, 17, 1);
  EXPECT_FALSE(identical(a, other_channel));
}

TEST(Generator, ChunkSizesDoNotChangeTheSamples) {
  ChannelSpec spec;
  spec.noise = full_model();
  const std::size_t n = 20000;
  const auto whole = simulate(spec, 200.0, n, 5);
  ChannelGenerator g(spec, 200.0, static_cast<double>(n) / 200.0, 5, 0);
  std::vector<double> pieces(n);
  std::size_t at = 0;
  Xoshiro256StarStar sizes(1);
  while (at < n) {
    const std::size_t len = std::min<std::size_t>(n - at, 1 + sizes() % 1500);
    g.generate(std::span<double>(pieces).subspan(at, len));
    at += len;
  }
  EXPECT_TRUE(identical(whole, pieces));
  EXPECT_EQ(g.position(), n);
}

TEST(Generator, ThreadCountDoesNotChangeTheSamples) {
  SimulationSpec spec;
  spec.rate_hz = 200.0;
  spec.duration_s = 100.0;
  spec.seed = 3;
  for (int c = 0; c < 5; ++c) spec.channels.push_back({full_model(), {}, ""});
  std::vector<std::vector<double>> runs;
  for (const unsigned threads : {1U, 2U, 3U, 8U}) {
    Generator g(spec);
    std::vector<double> all;
    std::vector<double> chunk(5 * 777);
    while (const std::size_t frames = g.generate_interleaved(chunk, threads)) {
      all.insert(all.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(frames * 5));
    }
    EXPECT_EQ(all.size(), 5U * 20000U);
    runs.push_back(all);
  }
  for (std::size_t i = 1; i < runs.size(); ++i) EXPECT_TRUE(identical(runs[0], runs[i])) << i;
  // Channel c of the multi-channel run is the single-channel stream with index c.
  const auto third = simulate(full_model(), 200.0, 20000, 3, 2);
  for (std::size_t k = 0; k < 20000; ++k) ASSERT_EQ(bits(runs[0][k * 5 + 2]), bits(third[k])) << k;
}

// Golden fingerprints: the first 4096 samples of TG-100 gyro 3 (Q, N, B, K; channel stream 1)
// and of a model with every term (channel stream 0). The expected values come from the
// independent Python re-implementation tests/sim/reference/sim_reference.py (IEEE doubles, no
// fused multiply-add), so they hold for any compiler, optimisation level (-O0 to
// -march=native) and platform; any change to the generator's arithmetic changes them.
TEST(Generator, GoldenFingerprintsFromIndependentReimplementation) {
  const Preset tg = find_preset("tg100");
  const auto a = simulate(tg.channels[2], 200.0, 4096, 1, 1);
  const auto b = simulate(full_model(), 200.0, 4096, 42, 0);
  EXPECT_EQ(fingerprint(a), 0x4d8165db798b0e3aULL) << std::hex << fingerprint(a);
  EXPECT_EQ(fingerprint(b), 0x1f99908e5251867aULL) << std::hex << fingerprint(b);
}

TEST(Generator, ModelIsTheBitwiseSumOfItsTermsSimulatedAlone) {
  const NoiseModel all = full_model();
  const std::size_t n = 6000;
  const double rate = 100.0;
  // Terms in the generator's summation order: Q, N, B, K, R, GM, sine, bias.
  std::vector<NoiseModel> terms(8);
  terms[0].q_unit_s = all.q_unit_s;
  terms[1].n_unit_sqrt_s = all.n_unit_sqrt_s;
  terms[2].b_unit = all.b_unit;
  terms[3].k_unit_per_sqrt_s = all.k_unit_per_sqrt_s;
  terms[4].r_unit_per_s = all.r_unit_per_s;
  terms[5].gm_sigma_unit = all.gm_sigma_unit;
  terms[5].gm_time_s = all.gm_time_s;
  terms[6].sine_amplitude_unit = all.sine_amplitude_unit;
  terms[6].sine_frequency_hz = all.sine_frequency_hz;
  terms[6].sine_phase_rad = all.sine_phase_rad;
  terms[7].bias_unit = all.bias_unit;
  // The flicker range defaults depend on the duration only, the same for every run.
  std::vector<double> sum(n, 0.0);
  for (const auto& t : terms) {
    const auto part = simulate(t, rate, n, 9);
    for (std::size_t k = 0; k < n; ++k) sum[k] += part[k];
  }
  EXPECT_TRUE(identical(simulate(all, rate, n, 9), sum));
}

TEST(Generator, WhiteNoisePerSampleSigmaIsNOverSqrtDt) {
  // N = 8.9e-4 deg/sqrt(s) at 200 Hz: sigma = 8.9e-4 / sqrt(0.005) = 0.01259 deg/s
  // (references.md). With n = 2^20 samples, (n - 1) s^2 / sigma^2 ~ chi^2(n - 1): the
  // normal approximation's two-sided 1e-5 band is sigma^2 (1 +- 4.42 sqrt(2/n)).
  NoiseModel m;
  m.n_unit_sqrt_s = 8.9e-4;
  const std::size_t n = std::size_t{1} << 20;
  const auto y = simulate(m, 200.0, n, 77);
  double mean = 0.0;
  for (const double v : y) mean += v;
  mean /= static_cast<double>(n);
  double var = 0.0, lag1 = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    var += (y[k] - mean) * (y[k] - mean);
    if (k > 0) lag1 += (y[k] - mean) * (y[k - 1] - mean);
  }
  lag1 /= var;
  var /= static_cast<double>(n - 1);
  const double sigma = 8.9e-4 / std::sqrt(0.005);
  EXPECT_NEAR(sigma, 0.012586, 1e-6);
  const double z = 4.4172;
  EXPECT_LT(std::fabs(var / (sigma * sigma) - 1.0), z * std::sqrt(2.0 / static_cast<double>(n)));
  EXPECT_LT(std::fabs(mean), z * sigma / std::sqrt(static_cast<double>(n)));
  EXPECT_LT(std::fabs(lag1), z / std::sqrt(static_cast<double>(n)));  // white: no correlation
}

TEST(Generator, DeterministicTermsAreExactIntervalAverages) {
  NoiseModel m;
  m.r_unit_per_s = 2e-3;
  m.bias_unit = 0.5;
  const double rate = 50.0, h = 1.0 / rate;
  auto y = simulate(m, rate, 1000, 1);
  for (std::size_t k = 0; k < y.size(); ++k) {
    const double expected = 0.5 + 2e-3 * (static_cast<double>(k) + 0.5) * h;
    ASSERT_NEAR(y[k], expected, 1e-15) << k;
  }
  NoiseModel s;
  s.sine_amplitude_unit = 2.0;
  s.sine_frequency_hz = 3.0;
  s.sine_phase_rad = 1.0;
  y = simulate(s, rate, 100000, 1);
  const double w = 2.0 * std::numbers::pi * 3.0;
  for (std::size_t k = 0; k < y.size(); k += 37) {
    const double t0 = static_cast<double>(k) * h;
    // (1/h) int_t0^t0+h 2 sin(w t + 1) dt
    const double expected = 2.0 * (std::cos(w * t0 + 1.0) - std::cos(w * (t0 + h) + 1.0)) / (w * h);
    ASSERT_NEAR(y[k], expected, 1e-10) << k;
  }
}

TEST(Generator, QuantizationNoiseTelescopes) {
  // Samples are (e_{k+1} - e_k)/tau0: their integral is e_n - e_0, of std sqrt(2) Q whatever n.
  NoiseModel m;
  m.q_unit_s = 1e-3;
  const auto y = simulate(m, 100.0, 100000, 4);
  double angle = 0.0;
  for (const double v : y) angle += v * 0.01;
  EXPECT_LT(std::fabs(angle), 4.42 * std::sqrt(2.0) * 1e-3);
}

TEST(Generator, OutputStage) {
  ChannelSpec plain;
  plain.noise.n_unit_sqrt_s = 1.0;  // sample std 10 at 100 Hz
  plain.noise.bias_unit = 3.0;
  const auto y = simulate(plain, 100.0, 20000, 8);

  ChannelSpec clipped = plain;
  clipped.output.range_unit = 12.0;
  const auto c = simulate(clipped, 100.0, 20000, 8);
  int saturated = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    ASSERT_EQ(c[k], std::clamp(y[k], -12.0, 12.0));
    saturated += std::fabs(c[k]) == 12.0;
  }
  EXPECT_GT(saturated, 1000);

  ChannelSpec volts = plain;
  volts.output.scale_factor = kTg100VoltsPerDegPerSecond;
  volts.output.offset_output = 2.5;
  const auto v = simulate(volts, 100.0, 20000, 8);
  // DOUBLE_EQ: this file may be compiled with FMA contraction, the generator never is.
  for (std::size_t k = 0; k < y.size(); ++k) ASSERT_DOUBLE_EQ(v[k], 0.02 * y[k] + 2.5);

  ChannelSpec adc = volts;
  adc.output.lsb_output = 5.0 / 65536.0;  // 16-bit ADC over 5 V
  const auto q = simulate(adc, 100.0, 20000, 8);
  for (std::size_t k = 0; k < y.size(); ++k) {
    ASSERT_LE(std::fabs(q[k] - v[k]), adc.output.lsb_output / 2.0);
    const double steps = q[k] / adc.output.lsb_output;
    ASSERT_EQ(steps, std::nearbyint(steps));
  }
}

TEST(Generator, RecordLengthAndChannelNames) {
  SimulationSpec spec;
  spec.rate_hz = 200.0;
  spec.duration_s = 21600.0;
  spec.channels = find_preset("tg100").channels;
  Generator g(spec);
  EXPECT_EQ(g.sample_count(), 4320000U);
  EXPECT_EQ(g.channel_count(), 4U);
  EXPECT_EQ(g.channel_name(2), "gyro3");
  // The generator's model has its flicker range resolved to [tau0, duration].
  EXPECT_DOUBLE_EQ(g.channel(0).model().flicker_tau_min_s, 0.005);
  EXPECT_DOUBLE_EQ(g.channel(0).model().flicker_tau_max_s, 21600.0);
  EXPECT_EQ(g.channel(0).flicker_bank().poles.size(), 15U);
}

namespace {

void expect_input_error(const NoiseModel& m, double rate, double duration, const std::string& fragment) {
  ChannelSpec spec;
  spec.noise = m;
  try {
    ChannelGenerator g(spec, rate, duration, 1, 0);
    ADD_FAILURE() << "no error for: " << fragment;
  } catch (const imunoise::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Generator, BadInputIsRejectedWithAClearMessage) {
  NoiseModel m;
  m.n_unit_sqrt_s = -1.0;
  expect_input_error(m, 200.0, 10.0, "N = -1 is negative");
  m = {};
  m.b_unit = NAN;
  expect_input_error(m, 200.0, 10.0, "B = nan is not a finite number");
  m = {};
  m.k_unit_per_sqrt_s = INFINITY;
  expect_input_error(m, 200.0, 10.0, "K = inf");
  m = {};
  expect_input_error(m, 200.0, 0.0, "duration = 0 s must be positive");
  expect_input_error(m, 0.0, 10.0, "rate = 0 Hz");
  expect_input_error(m, 200.0, 0.001, "shorter than one sample");
  m.sine_amplitude_unit = 1.0;
  m.sine_frequency_hz = 150.0;
  expect_input_error(m, 200.0, 10.0, "below twice the sinusoid frequency");
  m = {};
  m.gm_sigma_unit = 1.0;
  expect_input_error(m, 200.0, 10.0, "correlation time");
  m = {};
  m.b_unit = 1.0;
  m.flicker_tau_min_s = 0.001;
  expect_input_error(m, 200.0, 10.0, "below the sample interval");
  m.flicker_tau_min_s = 0.01;
  m.flicker_tau_max_s = 1e11;
  expect_input_error(m, 200.0, 10.0, "decades");
  m.flicker_tau_max_s = 0.005;
  expect_input_error(m, 200.0, 10.0, "flicker-tau-max must exceed");
  ChannelSpec spec;
  spec.output.range_unit = 0.0;
  EXPECT_THROW(ChannelGenerator(spec, 200.0, 10.0, 1, 0), imunoise::InputError);
  spec.output = {};
  spec.output.scale_factor = 0.0;
  EXPECT_THROW(ChannelGenerator(spec, 200.0, 10.0, 1, 0), imunoise::InputError);
  spec.output = {};
  spec.output.lsb_output = -1.0;
  EXPECT_THROW(ChannelGenerator(spec, 200.0, 10.0, 1, 0), imunoise::InputError);
  EXPECT_THROW(find_preset("tg200"), imunoise::InputError);
}
