// Streaming and merging, for the whole mergeable family (adev oadev mdev tdev hdev ohdev): pieces
// give the one-pass result (to rounding), merge is associative, the empty accumulator is the
// identity, the result does not depend on the absolute level of each piece, images round-trip.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "imunoise/deviation.hpp"
#include "imunoise/difference_accumulator.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"

namespace imunoise {
namespace {

constexpr double kTau0 = 0.01;
// Same terms, different summation order and a constant shift of each piece's phase: the
// difference is rounding, ~1e-15 relative observed; 1e-11 leaves room for the shift.
constexpr double kTolerance = 1e-11;

std::vector<double> rate_samples(std::size_t n) {
  std::mt19937_64 engine(99);
  std::vector<double> y(n);
  for (auto& v : y) v = 5.0 + static_cast<double>(engine() >> 11) * 0x1.0p-53;
  return y;
}

const std::vector<std::size_t> kFactors{1, 2, 3, 7, 16, 100, 1000, 2500};

void expect_same(const std::vector<DevPoint>& got, const std::vector<DevPoint>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].n, want[i].n) << "m=" << want[i].m;
    EXPECT_NEAR(got[i].dev / want[i].dev, 1.0, kTolerance) << "m=" << want[i].m;
  }
}

class Accumulate : public ::testing::TestWithParam<Estimator> {};

TEST_P(Accumulate, PushingPiecesEqualsOnePass) {
  const auto rate = rate_samples(30011);
  const auto phase = phase_from_rate(rate, kTau0, 5.5);
  const auto want = compute_deviation(GetParam(), phase, kTau0, kFactors);
  DifferenceAccumulator acc(GetParam(), kFactors);
  std::mt19937_64 engine(3);
  for (std::size_t begin = 0; begin < phase.size();) {
    const std::size_t len = std::min<std::size_t>(1 + engine() % 4000, phase.size() - begin);
    acc.push(std::span(phase).subspan(begin, len));
    begin += len;
  }
  EXPECT_EQ(acc.size(), phase.size());
  expect_same(acc.deviations(kTau0), want);
}

// Rate chunks integrated separately (each phase piece starts at 0, with the same offset) and
// merged: sequentially, as a tree, and with pieces shorter than the largest stencil.
TEST_P(Accumulate, MergingSeparatelyIntegratedChunksEqualsOnePass) {
  const auto rate = rate_samples(30011);
  const auto want = compute_deviation(GetParam(), phase_from_rate(rate, kTau0, 5.5), kTau0, kFactors);
  for (const std::size_t chunk : {std::size_t{997}, std::size_t{6000}, std::size_t{12000}}) {
    std::vector<DifferenceAccumulator> parts;
    for (std::size_t begin = 0; begin < rate.size(); begin += chunk) {
      const auto piece = std::span(rate).subspan(begin, std::min(chunk, rate.size() - begin));
      parts.emplace_back(GetParam(), kFactors, begin);  // adev/hdev: global start index
      parts.back().push(phase_from_rate(piece, kTau0, 5.5));
    }
    DifferenceAccumulator sequential(GetParam(), kFactors);
    for (const auto& part : parts) sequential.merge(part);
    expect_same(sequential.deviations(kTau0), want);
    EXPECT_EQ(sequential.size(), rate.size() + 1);

    // Pairwise tree: ((p0 p1) (p2 p3)) ...
    while (parts.size() > 1) {
      std::vector<DifferenceAccumulator> next;
      for (std::size_t i = 0; i + 1 < parts.size(); i += 2) {
        next.push_back(parts[i]);
        next.back().merge(parts[i + 1]);
      }
      if (parts.size() % 2 == 1) next.push_back(parts.back());
      parts = std::move(next);
    }
    expect_same(parts[0].deviations(kTau0), want);
  }
}

TEST_P(Accumulate, EmptyAccumulatorIsIdentity) {
  const auto phase = phase_from_rate(rate_samples(9000), kTau0, 5.5);
  DifferenceAccumulator full(GetParam(), kFactors), empty(GetParam(), kFactors);
  full.push(phase);
  DifferenceAccumulator left = empty;
  left.merge(full);
  DifferenceAccumulator right = full;
  right.merge(empty);
  const auto want = full.deviations(kTau0);
  for (const auto* acc : {&left, &right}) {
    const auto got = acc->deviations(kTau0);
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].n, want[i].n);
      if (want[i].n > 0) {
        EXPECT_EQ(got[i].dev, want[i].dev);
      }
    }
  }
}

// Pieces whose phase sits at wildly different levels (each piece + its own 2^30 multiple):
// the edges are kept relative to their boundary sample, so the merge never subtracts the
// levels. The phase is dyadic (multiples of 2^-20 below 2^10), so every level-shifted value is
// exact and the merged sums must be bitwise those of the unshifted pieces.
TEST_P(Accumulate, HugeLevelsOfThePiecesCancelExactly) {
  std::mt19937_64 engine(17);
  std::vector<double> phase(20000);
  double x = 0.0;
  for (auto& v : phase) {
    x += static_cast<double>(static_cast<std::int64_t>(engine() % 2001) - 1000) * 0x1.0p-20;
    v = x;
  }
  const auto want = compute_deviation(GetParam(), phase, kTau0, kFactors);
  DifferenceAccumulator plain(GetParam(), kFactors), lifted(GetParam(), kFactors);
  const std::size_t cut[] = {0, 4000, 9000, 9500, 19999};
  for (std::size_t i = 0; i + 1 < std::size(cut); ++i) {
    const auto piece = std::span(phase).subspan(cut[i], cut[i + 1] - cut[i] + 1);
    DifferenceAccumulator a(GetParam(), kFactors, cut[i]), b(GetParam(), kFactors, cut[i]);
    a.push(piece);
    std::vector<double> high(piece.begin(), piece.end());
    const double level = static_cast<double>((i % 2 == 0 ? 1 : -1) * static_cast<long long>(i + 1)) * 0x1.0p30;
    for (auto& v : high) v += level;
    b.push(high);
    plain.merge(a);
    lifted.merge(b);
  }
  const auto got_plain = plain.deviations(kTau0);
  const auto got_lifted = lifted.deviations(kTau0);
  expect_same(got_plain, want);
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got_lifted[i].dev, got_plain[i].dev) << "m=" << want[i].m;
  }
}

// Pushing after a merge continues in the merged accumulator's coordinates.
TEST_P(Accumulate, PushAfterMergeContinues) {
  const auto phase = phase_from_rate(rate_samples(12000), kTau0, 5.5);
  const auto want = compute_deviation(GetParam(), phase, kTau0, kFactors);
  DifferenceAccumulator a(GetParam(), kFactors), b(GetParam(), kFactors, 3000);
  a.push(std::span(phase).first(3001));
  std::vector<double> shifted(phase.begin() + 3000, phase.begin() + 9001);
  for (auto& v : shifted) v -= 123.25;  // b's own coordinates
  b.push(shifted);
  a.merge(b);
  a.push(std::span(phase).subspan(9001));
  expect_same(a.deviations(kTau0), want);
}

TEST_P(Accumulate, ByteImageRoundTrips) {
  const auto phase = phase_from_rate(rate_samples(9000), kTau0, 5.5);
  DifferenceAccumulator a(GetParam(), kFactors, 0), b(GetParam(), kFactors, 4000);
  a.push(std::span(phase).first(4001));
  b.push(std::span(phase).subspan(4000));
  auto a2 = DifferenceAccumulator::from_bytes(a.to_bytes());
  const auto b2 = DifferenceAccumulator::from_bytes(b.to_bytes());
  a.merge(b);
  a2.merge(b2);
  const auto want = a.deviations(kTau0), got = a2.deviations(kTau0);
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].n, want[i].n);
    if (want[i].n > 0) {
      EXPECT_EQ(got[i].dev, want[i].dev);
    }
  }
  auto bytes = a.to_bytes();
  bytes.pop_back();
  EXPECT_THROW(DifferenceAccumulator::from_bytes(bytes), InputError);
}

INSTANTIATE_TEST_SUITE_P(Core, Accumulate,
                         ::testing::Values(Estimator::adev, Estimator::oadev, Estimator::mdev,
                                           Estimator::tdev, Estimator::hdev, Estimator::ohdev),
                         [](const auto& param_info) { return std::string(estimator_name(param_info.param)); });

TEST(Accumulate, RejectsOtherEstimatorsAndMismatchedMerges) {
  EXPECT_THROW(DifferenceAccumulator(Estimator::totdev, {1}), InputError);
  DifferenceAccumulator a(Estimator::oadev, {1, 2}), b(Estimator::oadev, {1, 4});
  EXPECT_THROW(a.merge(b), InputError);
  // adev/hdev pieces must be adjacent: the term alignment (k = 0, m, 2m) depends on it.
  DifferenceAccumulator c(Estimator::adev, {1, 2}, 0), d(Estimator::adev, {1, 2}, 7);
  c.push(std::vector<double>(5, 1.0));
  d.push(std::vector<double>(5, 1.0));
  EXPECT_THROW(c.merge(d), InputError);
}

}  // namespace
}  // namespace imunoise
