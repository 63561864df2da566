// One record sliced over ranks (thread ranks here; tests/fleet runs mpirun): the merged curves
// equal the estimators run on the whole loaded record, for raw binary slices read by every
// rank and for a text file scattered by rank 0; a bad sample in one rank's slice stops every
// rank with the file's message. The tolerance 1e-12 relative: the same terms are summed, only
// in another order and from each slice's own integration origin (~1e-15 seen).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/parallel/distributed_deviations.hpp"
#include "imunoise/theo.hpp"
#include "parallel/thread_ranks.hpp"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;

constexpr double kRelative = 1e-12;
constexpr double kRateHz = 100.0;

std::vector<double> white_plus_walk(std::size_t n) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> rate(n);
  double walk = 0.0;
  for (auto& r : rate) {
    walk += 1e-3 * g(rng);
    r = 0.5 + 1e-2 * g(rng) + walk;
  }
  return rate;
}

class Scratch {
 public:
  Scratch() : dir_(fs::temp_directory_path() / ("imunoise-parallel-" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
  }
  ~Scratch() { fs::remove_all(dir_); }
  fs::path operator/(const std::string& name) const { return dir_ / name; }

 private:
  fs::path dir_;
};

std::string write_binary(const fs::path& path, const std::vector<double>& rate) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(rate.data()), static_cast<std::streamsize>(rate.size() * sizeof(double)));
  return path.string();
}

std::string write_text(const fs::path& path, const std::vector<double>& rate) {
  std::ofstream out(path);
  out.precision(17);
  for (double r : rate) out << r << '\n';
  return path.string();
}

const std::vector<Estimator> kMergeable{Estimator::adev, Estimator::oadev, Estimator::mdev,
                                        Estimator::tdev, Estimator::hdev, Estimator::ohdev};

// The same estimators on the whole record, loaded the serial way.
std::vector<std::vector<DevPoint>> serial_curves(const load::LoadOptions& input, const TauGrid& grid) {
  const Record record = load::load(input);
  std::vector<std::vector<DevPoint>> curves;
  for (const Estimator e : kMergeable) {
    const auto m = estimator_averaging_factors(e, grid, record.rate_hz, record.phase_si.size());
    curves.push_back(compute_deviation(e, record.phase_si, 1.0 / record.rate_hz, m));
  }
  return curves;
}

void expect_curves_equal(const std::vector<std::vector<DevPoint>>& got,
                         const std::vector<std::vector<DevPoint>>& want, int size) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t e = 0; e < want.size(); ++e) {
    ASSERT_EQ(got[e].size(), want[e].size()) << estimator_name(kMergeable[e]) << ", " << size << " ranks";
    for (std::size_t i = 0; i < want[e].size(); ++i) {
      EXPECT_EQ(got[e][i].m, want[e][i].m);
      EXPECT_EQ(got[e][i].n, want[e][i].n);
      EXPECT_NEAR(got[e][i].dev / want[e][i].dev, 1.0, kRelative)
          << estimator_name(kMergeable[e]) << " m=" << want[e][i].m << ", " << size << " ranks";
    }
  }
}

void expect_slices_join(const load::LoadOptions& input) {
  const TauGrid grid = parse_tau_grid("octave");
  const auto want = serial_curves(input, grid);
  for (int size = 1; size <= 4; ++size) {
    parallel::DistributedCurves root;
    const auto errors = run_ranks(size, [&](parallel::Ranks& ranks) {
      auto out = parallel::distributed_deviations(ranks, input, kMergeable, grid);
      EXPECT_EQ(out.root, ranks.rank() == 0);
      if (out.root) root = std::move(out);
    });
    for (const auto& e : errors) EXPECT_FALSE(e) << size << " ranks";
    EXPECT_EQ(root.n_phase, 20001u);
    EXPECT_EQ(root.record.n_samples, 20000u);
    expect_curves_equal(root.curves, want, size);
  }
}

TEST(DistributedDeviations, BinarySlicesJoinIntoTheWholeRecord) {
  Scratch scratch;
  load::LoadOptions input;
  input.file = write_binary(scratch / "rate.f64", white_plus_walk(20000));
  input.binary = "f64";
  input.rate_hz = kRateHz;
  expect_slices_join(input);
}

TEST(DistributedDeviations, TextScatteredByRankZeroJoinsIntoTheWholeRecord) {
  Scratch scratch;
  load::LoadOptions input;
  input.file = write_text(scratch / "rate.txt", white_plus_walk(20000));
  input.rate_hz = kRateHz;
  expect_slices_join(input);
}

TEST(DistributedDeviations, BadSampleInOneSliceStopsEveryRankWithTheFile) {
  Scratch scratch;
  auto rate = white_plus_walk(20000);
  rate[17000] = std::nan("");  // in the last rank's slice
  load::LoadOptions input;
  input.file = write_binary(scratch / "bad.f64", rate);
  input.binary = "f64";
  input.rate_hz = kRateHz;
  const auto errors = run_ranks(3, [&](parallel::Ranks& ranks) {
    parallel::distributed_deviations(ranks, input, {Estimator::oadev}, parse_tau_grid("octave"));
  });
  // The rank that meets the sample names it (rank 0 may, reading the first 2^20 samples for
  // the rate offset); every other rank stops saying why.
  int naming = 0;
  for (std::size_t r = 0; r < errors.size(); ++r) {
    ASSERT_TRUE(errors[r]) << "rank " << r << " went on";
    try {
      std::rethrow_exception(errors[r]);
    } catch (const InputError& e) {
      const std::string what = e.what();
      if (what.find("bad.f64: record 17000") != std::string::npos) {
        ++naming;
      } else {
        EXPECT_NE(what.find("another rank failed"), std::string::npos) << what;
      }
    }
  }
  EXPECT_GE(naming, 1);
}

TEST(DistributedDeviations, NonMergeableEstimatorIsRefused) {
  parallel::SingleRank one;
  load::LoadOptions input;
  input.file = "unused.txt";
  EXPECT_THROW(parallel::distributed_deviations(one, input, {Estimator::totdev}, parse_tau_grid("octave")),
               InputError);
}

}  // namespace
}  // namespace imunoise::test
