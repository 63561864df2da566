// Streaming and merging: pieces give the one-pass result (to rounding), merge is associative,
// the empty accumulator is the identity.
#include <gtest/gtest.h>

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
      parts.emplace_back(GetParam(), kFactors);
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

INSTANTIATE_TEST_SUITE_P(Core, Accumulate, ::testing::Values(Estimator::oadev, Estimator::ohdev),
                         [](const auto& param_info) { return std::string(estimator_name(param_info.param)); });

TEST(Accumulate, RejectsOtherEstimatorsAndMismatchedMerges) {
  EXPECT_THROW(DifferenceAccumulator(Estimator::mdev, {1}), InputError);
  DifferenceAccumulator a(Estimator::oadev, {1, 2}), b(Estimator::oadev, {1, 4});
  EXPECT_THROW(a.merge(b), InputError);
}

}  // namespace
}  // namespace imunoise
