#pragma once
// Random numbers for the simulator: a specified generator and a specified normal transform,
// so that a seed gives the same samples on every run, thread count, compiler and platform.
//
// - Uniform bits: xoshiro256** 1.0 (D. Blackman and S. Vigna, "Scrambled linear pseudorandom
//   number generators", ACM TOMS 47(4), 2021): 256-bit state, period 2^256 - 1, passes
//   BigCrush and PractRand; jump() and long_jump() advance it by 2^128 and 2^192 draws, which
//   gives non-overlapping streams (one per channel and noise term). A 64-bit seed is expanded
//   into the state with SplitMix64 (G. Steele, D. Lea, C. Flood, OOPSLA 2014), as the authors
//   recommend.
// - Normal variates: our own 256-layer ziggurat (G. Marsaglia and W. Tsang, J. Stat. Softw.
//   5(8), 2000) with the improvements of J. Doornik (2005): the layer index, the sign and the
//   53-bit abscissa come from disjoint bits of one 64-bit draw, so they are independent. The
//   layer table is computed once in 60-digit arithmetic and stored as exact double literals
//   (src/sim/ziggurat_tables.inc); the wedge and tail tests use portable::exp and
//   portable::log. The method is exact: it returns N(0, 1) variates up to the 2^-53
//   resolution of the uniform abscissa and the rounding of the table (both ~1e-16 relative);
//   std::normal_distribution is not used because its algorithm differs between libraries.
//   Cost: one 64-bit draw and one comparison per variate 98.5 % of the time.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

namespace imunoise::sim {

/// SplitMix64: a 64-bit counter through a bijective mixer; used to expand seeds.
class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  constexpr std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

/// xoshiro256**: satisfies std::uniform_random_bit_generator.
class Xoshiro256StarStar {
 public:
  using result_type = std::uint64_t;
  using State = std::array<std::uint64_t, 4>;

  /// State from a 64-bit seed: four successive SplitMix64 outputs (never all zero).
  explicit Xoshiro256StarStar(std::uint64_t seed) noexcept;
  /// State given directly; must not be all zero (an all-zero state is replaced by seed 0's).
  explicit Xoshiro256StarStar(const State& state) noexcept;

  static constexpr result_type min() noexcept { return 0; }
  static constexpr result_type max() noexcept { return std::numeric_limits<result_type>::max(); }

  result_type operator()() noexcept {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// Uniform double in [0, 1) with 53 random bits: (draw >> 11) * 2^-53.
  double uniform() noexcept {
    return static_cast<double>(static_cast<std::int64_t>((*this)() >> 11)) * 0x1.0p-53;
  }

  /// Advances the state by 2^128 draws.
  void jump() noexcept;
  /// Advances the state by 2^192 draws.
  void long_jump() noexcept;

  const State& state() const noexcept { return s_; }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept {
    return (x << k) | (x >> (64 - k));
  }
  void apply_jump(const State& polynomial) noexcept;

  State s_;
};

/// The stream of one (channel, noise term) pair: seed expanded by SplitMix64, then
/// `channel` long jumps (2^192 draws each) and `term` jumps (2^128 draws each). Streams of
/// different pairs never overlap for any realistic length (< 2^128 draws).
Xoshiro256StarStar make_stream(std::uint64_t seed, std::uint64_t channel, std::uint64_t term);

/// Standard normal variates by the ziggurat described above.
class NormalGenerator {
 public:
  explicit NormalGenerator(const Xoshiro256StarStar& engine) noexcept : engine_(engine) {}

  /// One N(0, 1) variate.
  double operator()() noexcept;

  /// Fills `out` with successive variates; identical to calling operator() out.size() times.
  void fill(std::span<double> out) noexcept;

  const Xoshiro256StarStar& engine() const noexcept { return engine_; }

 private:
  double slow_path(std::uint64_t bits) noexcept;

  Xoshiro256StarStar engine_;
};

}  // namespace imunoise::sim
