#include "deterministic_fp.hpp"  // first: no fused multiply-add in this file

#include "imunoise/sim/rng.hpp"

#include <bit>

#include "imunoise/sim/portable_math.hpp"

namespace imunoise::sim {
namespace {

#include "ziggurat_tables.inc"

// Jump polynomials of xoshiro256 (published with the generator): x^(2^128) and x^(2^192)
// modulo its characteristic polynomial, as 256-bit masks. Checked independently in
// tests/sim/rng_test.cpp against a GF(2) matrix power.
constexpr Xoshiro256StarStar::State kJump = {0x180ec6d33cfd0abaULL, 0xd5a61266f0c9392cULL,
                                             0xa9582618e03fc9aaULL, 0x39abdc4529b1661cULL};
constexpr Xoshiro256StarStar::State kLongJump = {0x76e15d3efefdcbbfULL, 0xc5004e441c522fb3ULL,
                                                 0x77710069854ee241ULL, 0x39109bb02acbe635ULL};

Xoshiro256StarStar::State expand_seed(std::uint64_t seed) noexcept {
  SplitMix64 sm(seed);
  Xoshiro256StarStar::State s{};
  for (auto& word : s) word = sm.next();
  return s;
}

// One ziggurat attempt's fast path: layer i = low 8 bits, sign = bit 8, abscissa = top 53
// bits. Returns true and sets x when the point falls in the part of the layer that lies
// entirely under the curve.
inline bool fast_normal(std::uint64_t bits, double& x) noexcept {
  const unsigned layer = static_cast<unsigned>(bits & 0xffU);
  // The top 53 bits fit an int64, whose conversion to double is one instruction.
  const double u = static_cast<double>(static_cast<std::int64_t>(bits >> 11)) * 0x1.0p-53;
  const double a = u * kZigguratX[layer];
  if (a < kZigguratX[layer + 1]) {
    // Branch-free sign (a 50 % branch would be mispredicted half the time): bit 8 -> bit 63.
    x = std::bit_cast<double>(std::bit_cast<std::uint64_t>(a) ^ ((bits & 0x100U) << 55));
    return true;
  }
  return false;
}

}  // namespace

Xoshiro256StarStar::Xoshiro256StarStar(std::uint64_t seed) noexcept : s_(expand_seed(seed)) {}

Xoshiro256StarStar::Xoshiro256StarStar(const State& state) noexcept : s_(state) {
  if ((s_[0] | s_[1] | s_[2] | s_[3]) == 0) s_ = expand_seed(0);
}

void Xoshiro256StarStar::apply_jump(const State& polynomial) noexcept {
  State acc{};
  for (const std::uint64_t word : polynomial) {
    for (int b = 0; b < 64; ++b) {
      if (word & (std::uint64_t{1} << b)) {
        for (int w = 0; w < 4; ++w) acc[w] ^= s_[w];
      }
      (*this)();
    }
  }
  s_ = acc;
}

void Xoshiro256StarStar::jump() noexcept { apply_jump(kJump); }
void Xoshiro256StarStar::long_jump() noexcept { apply_jump(kLongJump); }

Xoshiro256StarStar make_stream(std::uint64_t seed, std::uint64_t channel, std::uint64_t term) {
  Xoshiro256StarStar engine(seed);
  for (std::uint64_t c = 0; c < channel; ++c) engine.long_jump();
  for (std::uint64_t t = 0; t < term; ++t) engine.jump();
  return engine;
}

double NormalGenerator::operator()() noexcept {
  const std::uint64_t bits = engine_();
  double x;
  if (fast_normal(bits, x)) return x;
  return slow_path(bits);
}

void NormalGenerator::fill(std::span<double> out) noexcept {
  // Same sequence as repeated operator() calls; the loop keeps the engine state in registers.
  Xoshiro256StarStar engine = engine_;
  for (double& value : out) {
    const std::uint64_t bits = engine();
    double x;
    if (fast_normal(bits, x)) {
      value = x;
    } else {
      engine_ = engine;
      value = slow_path(bits);
      engine = engine_;
    }
  }
  engine_ = engine;
}

// The rest of the ziggurat: the wedge of a layer, the tail beyond r, and retries. `bits` is the
// draw that missed the fast path.
double NormalGenerator::slow_path(std::uint64_t bits) noexcept {
  for (;;) {
    const unsigned layer = static_cast<unsigned>(bits & 0xffU);
    const bool negative = (bits & 0x100U) != 0;
    const double u = static_cast<double>(static_cast<std::int64_t>(bits >> 11)) * 0x1.0p-53;
    const double a = u * kZigguratX[layer];
    if (a < kZigguratX[layer + 1]) return negative ? -a : a;
    if (layer == 0) {
      // Tail x > r (Marsaglia 1964): a = -ln(u1)/r, b = -ln(u2), accept when 2b > a^2.
      // 1 - uniform() lies in (0, 1], so the logarithms are finite.
      for (;;) {
        const double ta = -portable::log(1.0 - engine_.uniform()) * kZigguratInvR;
        const double tb = -portable::log(1.0 - engine_.uniform());
        if (tb + tb > ta * ta) {
          const double x = kZigguratR + ta;
          return negative ? -x : x;
        }
      }
    }
    // Wedge: the point (a, y) with y uniform over the layer's height lies under the curve?
    const double y = kZigguratF[layer] + engine_.uniform() * (kZigguratF[layer + 1] - kZigguratF[layer]);
    if (y < portable::exp(-0.5 * a * a)) return negative ? -a : a;
    bits = engine_();  // rejected: start a new attempt
  }
}

}  // namespace imunoise::sim
