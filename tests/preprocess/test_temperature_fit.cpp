// The full noise-model fit per temperature bin: a simulated record whose angle random walk N
// steps up with temperature is fitted bin by bin, each bin's N interval holds that bin's true N
// and the hot and cold bins' intervals are apart; the bins reach the JSON document and the
// `fit --temperature` command.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/preprocess/temperature.hpp"
#include "imunoise/units.hpp"

namespace imunoise::preprocess {
namespace {

// 100 Hz, 4000 s: the temperature ramps 10 -> 40 -> 10 degC twice; white rate noise of sd 1e-3
// rad/s below 25 degC and 3e-3 above (N = sd / sqrt(100 Hz)), plus a bias of 2e-4 (T - 25).
struct Simulated {
  std::vector<double> rate_si;
  std::vector<double> temperature;
};
Simulated simulate(std::size_t n) {
  Simulated s;
  std::mt19937_64 rng(41);
  std::normal_distribution<double> g(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double cycle = std::fmod(static_cast<double>(i) / (static_cast<double>(n) / 2.0), 1.0);
    const double t_c = std::min(10.0 + 30.0 * (cycle < 0.5 ? 2 * cycle : 2 - 2 * cycle), 39.999);
    s.temperature.push_back(t_c);
    s.rate_si.push_back(2e-4 * (t_c - 25.0) + (t_c >= 25.0 ? 3e-3 : 1e-3) * g(rng));
  }
  return s;
}

double true_n(double bin_low) { return (bin_low >= 25.0 ? 3e-3 : 1e-3) / std::sqrt(100.0); }

TEST(TemperatureFit, EachBinsFittedNHoldsItsTrueValue) {
  const auto s = simulate(400'000);
  fit::FitOptions options;
  // 99.9 % intervals: six bins each miss their truth with probability 1e-3 (0.6 % for any).
  options.level = 0.999;
  const auto bins = temperature_bins(s.rate_si, s.temperature, 100.0, 5.0, 1000, &options);
  ASSERT_EQ(bins.size(), 6u);
  double cold_high = 0.0;
  double hot_low = 1.0;
  for (const auto& b : bins) {
    SCOPED_TRACE("bin " + std::to_string(b.low));
    ASSERT_TRUE(b.fit.has_value()) << b.fit_error;
    const auto& n = b.fit->coefficients.random_walk;
    ASSERT_TRUE(n.identified);
    EXPECT_LE(n.ci_low, true_n(b.low));
    EXPECT_GE(n.ci_high, true_n(b.low));
    // The bias ramp inside a 5 degC bin (1e-3 rad/s over a pass) is a rate ramp, not K or B
    // large enough to move N: N dominates the short taus.
    if (b.low < 25.0) cold_high = std::max(cold_high, n.ci_high);
    else hot_low = std::min(hot_low, n.ci_low);
    EXPECT_GT(b.fit->summary.points_used, 3u);
  }
  EXPECT_LT(cold_high, hot_low);  // the step in N is resolved
  // The document: each bin carries the fit's terms (in the record unit) and diagnostics.
  fit::RecordInfo info{"sim", 100.0, s.rate_si.size(), parse_unit("rad/s"), "rad/s", true};
  const auto j = temperature_bins_json(bins, info, options);
  ASSERT_EQ(j.size(), 6u);
  for (std::size_t k = 0; k < bins.size(); ++k) {
    const auto& f = j[k].at("fit");
    EXPECT_EQ(f.at("source").get<std::string>().find("sim temperature ["), 0u);
    EXPECT_EQ(f.at("n_samples").get<std::size_t>(), bins[k].samples);
    EXPECT_DOUBLE_EQ(f.at("terms").at("N").at("value").get<double>(), bins[k].fit->coefficients.random_walk.value);
    EXPECT_TRUE(f.at("diagnostics").contains("chi2_dof"));
  }
  const auto lines = temperature_bins_lines(bins, info);
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_NE(lines[0].find("; N "), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("rad/sqrt(s)"), std::string::npos) << lines[0];
}

TEST(TemperatureFit, ABinTooShortToFitSaysWhyAndTheOthersAreStillFitted) {
  // 3000 samples of noise at 20 degC, then 1500 constant samples (a dead sensor) at 30 degC:
  // the second bin's curve is zero and cannot be fitted; that is said in its fit_error (never
  // thrown) and the first bin is still fitted.
  std::vector<double> rate(4500);
  std::vector<double> temperature(4500);
  std::mt19937_64 rng(42);
  std::normal_distribution<double> g(0.0, 1e-3);
  for (std::size_t i = 0; i < rate.size(); ++i) {
    rate[i] = g(rng);
    temperature[i] = i < 3000 ? 20.0 : 30.0;
  }
  for (std::size_t i = 3000; i < rate.size(); ++i) rate[i] = 0.0;  // a constant (dead) stretch
  fit::FitOptions options;
  const auto bins = temperature_bins(rate, temperature, 100.0, 5.0, 1000, &options);
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_TRUE(bins[0].fit.has_value()) << bins[0].fit_error;
  EXPECT_FALSE(bins[1].fit.has_value());
  EXPECT_NE(bins[1].fit_error.find("cannot fit a noise model"), std::string::npos) << bins[1].fit_error;
}

TEST(TemperatureFit, ARunEndsAtAGapBreakSoNoTermSpansTheGap) {
  // One bin throughout, a break at 5000: two runs, and the pooled curve has the two runs'
  // terms only (oadev at m = 1: (5000 - 1) + (5000 - 1) second differences).
  std::vector<double> rate(10'000);
  std::mt19937_64 rng(43);
  std::normal_distribution<double> g(0.0, 1e-3);
  for (auto& x : rate) x = g(rng);
  const std::vector<double> temperature(rate.size(), 21.0);
  const std::vector<std::size_t> breaks = {5000};
  const auto bins = temperature_bins(rate, temperature, 100.0, 5.0, 1000, nullptr, breaks);
  ASSERT_EQ(bins.size(), 1u);
  EXPECT_EQ(bins[0].segments, 2u);
  EXPECT_EQ(bins[0].samples, 10'000u);
  ASSERT_FALSE(bins[0].oadev.empty());
  EXPECT_EQ(bins[0].oadev[0].n, 2u * (5000 - 1));
  EXPECT_FALSE(bins[0].fit.has_value());  // no fit options: read-offs only
}

TEST(TemperatureFit, FitCommandReportsTheFitPerBin) {
  const auto s = simulate(200'000);
  const auto dir = std::filesystem::temp_directory_path() / ("imunoise_tfit_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "t.csv");
    out << "t,gx,temp_c\n";
    char line[96];
    for (std::size_t i = 0; i < s.rate_si.size(); ++i) {
      std::snprintf(line, sizeof line, "%.2f,%.9e,%.4f\n", static_cast<double>(i) / 100.0, s.rate_si[i], s.temperature[i]);
      out << line;
    }
  }
  const std::string command = std::string(IMUNOISE_CLI_PATH) + " fit '" + (dir / "t.csv").string() +
                              "' --time-column t --column gx --units rad/s --temperature temp_c --temperature-bin 15 "
                              "--level 0.999 --format json >" + (dir / "out").string() + " 2>" + (dir / "err").string();
  const int status = std::system(command.c_str());
  std::stringstream out;
  out << std::ifstream(dir / "out").rdbuf();
  std::stringstream err;
  err << std::ifstream(dir / "err").rdbuf();
  std::filesystem::remove_all(dir);
  ASSERT_EQ(status, 0) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  const auto& bins = j.at("temperature_bins");
  ASSERT_EQ(bins.size(), 3u);  // [0,15) [15,30) [30,45)
  // The [30, 45) bin is all hot (N = 3e-4 rad/sqrt(s)), the [0, 15) bin all cold (1e-4).
  const auto& cold = bins[0].at("fit").at("terms").at("N");
  const auto& hot = bins[2].at("fit").at("terms").at("N");
  EXPECT_EQ(cold.at("unit").get<std::string>(), "rad/sqrt(s)");
  EXPECT_LE(cold.at("ci_low").get<double>(), 1e-4);
  EXPECT_GE(cold.at("ci_high").get<double>(), 1e-4);
  EXPECT_LE(hot.at("ci_low").get<double>(), 3e-4);
  EXPECT_GE(hot.at("ci_high").get<double>(), 3e-4);
  EXPECT_EQ(bins[2].at("fit").at("level").get<double>(), 0.999);  // the command's fit options
}

}  // namespace
}  // namespace imunoise::preprocess
