#pragma once
// The noise simulator: streams samples of one or several sensor channels in chunks.
//
// Exactness. Every random term is generated from the exact joint distribution of its state
// and its average over each sample interval (see noise_model.hpp and gauss_markov.hpp), so
// the simulated sequence has exactly the second-order statistics of the continuous-time
// model averaged over each sample: white noise N / sqrt(tau0) per sample; the rate random
// walk through the exact pair (rate increment, integral of the Wiener process); Gauss-Markov
// and flicker poles through their exact one-interval update, started stationary; Q as white
// angle noise differenced; ramp, sinusoid (averaged over each interval:
// A sinc(pi f tau0) sin(2 pi f (k + 1/2) tau0 + phase)) and bias deterministic. The Allan
// variance of the output at tau = m tau0 is therefore the closed form of theory.hpp.
//
// Reproducibility. Every (channel c, term t) pair draws from its own xoshiro256** stream,
// make_stream(seed, c, t) (rng.hpp), in sample order, with terms numbered
//   0 Q, 1 N, 2 B (flicker bank), 3 K, 4 Gauss-Markov.
// Deterministic arithmetic only (no fused multiply-add, portable elementary functions), so
// the samples depend on nothing but the spec and the seed: not on the chunk sizes asked for,
// not on the thread count, not on the platform. Adding or removing one term leaves the
// others' samples unchanged, and the output of a model is, bit for bit, the sum of the
// outputs of its terms simulated alone (in the order Q, N, B, K, R, GM, sine, bias).
//
// Memory is bounded for any duration: about 4 kB per channel plus 4 kB per flicker pole.
// Speed (Release, one core, bench/bench_sim.cpp): see docs/simulator.md.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "imunoise/sim/flicker.hpp"
#include "imunoise/sim/gauss_markov.hpp"
#include "imunoise/sim/noise_model.hpp"
#include "imunoise/sim/rng.hpp"

namespace imunoise::sim {

/// One channel: its noise model, its output stage and a column name.
struct ChannelSpec {
  NoiseModel noise;
  OutputStage output;
  std::string name;  ///< empty: "ch<index+1>"
};

struct SimulationSpec {
  double rate_hz = 0.0;        ///< sample rate (Hz); tau0 = 1 / rate_hz
  double duration_s = 21600.0; ///< record length (s); sample count = round(duration * rate)
  std::uint64_t seed = 1;
  std::vector<ChannelSpec> channels;
};

/// Stream ids of the random terms (the `term` argument of make_stream).
enum class TermStream : std::uint64_t { quantization = 0, white = 1, flicker = 2, rate_random_walk = 3, gauss_markov = 4 };

/// The stream of one channel. Samples are produced in order; any split into generate() calls
/// yields the same samples.
class ChannelGenerator {
 public:
  /// Validates the model (validate, check_sampling) and throws InputError on bad input.
  /// duration_s only fixes the default flicker range (resolve_flicker_range).
  ChannelGenerator(const ChannelSpec& spec, double rate_hz, double duration_s, std::uint64_t seed,
                   std::uint64_t channel_index);

  /// Writes the next out.size() samples, in output units (after the output stage).
  void generate(std::span<double> out);

  /// Samples generated so far.
  std::uint64_t position() const { return index_; }
  double tau0_s() const { return tau0_s_; }
  /// The simulated model, flicker range resolved: pass it to theory.hpp for exact statistics.
  const NoiseModel& model() const { return model_; }
  const OutputStage& output() const { return output_; }
  const FlickerBank& flicker_bank() const { return bank_; }

 private:
  void add_terms(std::span<double> y);
  void apply_output_stage(std::span<double> y) const;

  NoiseModel model_;
  OutputStage output_;
  double tau0_s_;
  std::uint64_t index_ = 0;

  NormalGenerator q_normals_, white_normals_, flicker_normals_, rrw_normals_, gm_normals_;
  double q_previous_ = 0.0;       // angle noise at the start of the next sample (U*s)
  double white_per_sample_ = 0.0; // N / sqrt(tau0)
  double rrw_rate_ = 0.0;         // current rate random walk value (U)
  double rrw_half_ = 0.0, rrw_bridge_ = 0.0;
  GaussMarkovStep gm_step_{};
  double gm_state_ = 0.0;
  FlickerBank bank_;
  std::vector<double> pole_phi_, pole_noise_, pole_a_, pole_b_;  // per pole, GaussMarkovStep fields
  std::vector<double> pole_states_;
  double flicker_residual_ = 0.0;  // std of the merged independent part of the bank average
  double sine_gain_ = 0.0;         // A sinc(pi f tau0)
  double sine_cycles_per_sample_ = 0.0, sine_cycles0_ = 0.0;
  std::vector<double> normals_;    // scratch
};

/// Several channels generated together (independent streams, one per channel index).
class Generator {
 public:
  /// Validates everything up front (InputError names channel and parameter).
  explicit Generator(const SimulationSpec& spec);

  std::size_t channel_count() const { return channels_.size(); }
  /// Samples per channel in the whole record: round(duration * rate).
  std::uint64_t sample_count() const { return sample_count_; }
  std::uint64_t remaining() const { return sample_count_ - position_; }
  double rate_hz() const { return rate_hz_; }
  double tau0_s() const { return 1.0 / rate_hz_; }
  const ChannelGenerator& channel(std::size_t c) const { return channels_.at(c); }
  const std::string& channel_name(std::size_t c) const { return names_.at(c); }

  /// Next frames, interleaved (frame-major: ch0, ch1, ..., ch0, ...). out.size() must be a
  /// multiple of channel_count(). Writes min(out.size() / channels, remaining()) frames and
  /// returns that number (0 at the end). threads > 1 generates channels in parallel; the
  /// result does not depend on it.
  std::size_t generate_interleaved(std::span<double> out, unsigned threads = 1);

  /// Next frames into one buffer per channel (all of the same size n); writes
  /// min(n, remaining()) samples to each and returns that number.
  std::size_t generate_planar(std::span<const std::span<double>> out, unsigned threads = 1);

 private:
  double rate_hz_;
  std::uint64_t sample_count_;
  std::uint64_t position_ = 0;
  std::vector<ChannelGenerator> channels_;
  std::vector<std::string> names_;
  std::vector<double> scratch_;
};

/// Convenience: n_samples of one channel in memory (channel index selects the stream).
std::vector<double> simulate(const ChannelSpec& spec, double rate_hz, std::size_t n_samples,
                             std::uint64_t seed, std::uint64_t channel_index = 0);

/// Same, for a noise model with the default output stage.
std::vector<double> simulate(const NoiseModel& model, double rate_hz, std::size_t n_samples,
                             std::uint64_t seed, std::uint64_t channel_index = 0);

}  // namespace imunoise::sim
