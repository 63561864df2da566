// The default fit (short-tau cut, model mismatch, automatic terms) on real recordings:
// ADIS16405 MEMS IMUs, 100 Hz, six axes, read from ../shared/data relative to the repository root (IMUNOISE_SHARED_DATA overrides; the
// data's licence keeps them out of the repository, so the tests skip with a message when the
// folder is absent). Every file adis16405_unit*.csv found is checked with the same criteria:
// nothing is tuned to one unit.
//
// Criteria, each from the measured curve alone (no fitted constant):
//  - the fit converges and reports chi2/dof;
//  - the model's adev lies within the measured 95 % interval (chi-squared, fill_confidence)
//    widened by 15 % at every tau from 0.1 s, fitted or not (a tau the fit left out counts:
//    the model must still describe it);
//  - N within 10 % of the -1/2-slope value: sigma(tau) sqrt(tau), median over the first run of
//    consecutive taus (from the first fitted one) whose local log-log slope (from the
//    neighbours) is within 0.1 of -1/2: white noise shows first, after the sampling chain;
//  - B between 0.6 and 1.25 times min / 0.664 (the curve's minimum overstates the flicker floor
//    where N or K add to it: hence the asymmetric band).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "imunoise/allan.hpp"
#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/phase.hpp"

namespace {

using namespace imunoise;
namespace fs = std::filesystem;

constexpr double kRateHz = 100.0;
const char* const kColumns[6] = {"gyro_x_dps", "gyro_y_dps", "gyro_z_dps",
                                 "accel_x_g",  "accel_y_g",  "accel_z_g"};

fs::path shared_data() {
  if (const char* v = std::getenv("IMUNOISE_SHARED_DATA")) return v;
  // IMUNOISE_TEST_DATA_DIR is <repo>/tests/data.
  return fs::path(IMUNOISE_TEST_DATA_DIR).parent_path().parent_path().parent_path() / "shared" /
         "data";
}

/// IMUNOISE_REAL_SUBSET (set by the asan test preset, CMakePresets.json): the sanitizer run
/// checks memory, not the numbers, so it fits the first unit's gyro x and accelerometer z only
/// (the same code paths; 9x the Release time per axis under ASan). The default run checks every
/// axis of every unit.
bool sanitizer_subset() { return std::getenv("IMUNOISE_REAL_SUBSET") != nullptr; }

std::vector<fs::path> units() {
  std::vector<fs::path> files;
  std::error_code ec;
  const auto dir = shared_data();
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const auto name = e.path().filename().string();
    if (name.rfind("adis16405_unit", 0) == 0 && e.path().extension() == ".csv") {
      files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  if (sanitizer_subset() && files.size() > 1) files.resize(1);
  return files;
}

/// The axes checked: all six, or under the sanitizer subset one gyro and one accelerometer.
std::vector<int> axes() {
  if (sanitizer_subset()) return {0, 5};
  return {0, 1, 2, 3, 4, 5};
}

/// The six columns of a unit's CSV (header line first).
std::vector<std::vector<double>> read_columns(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> cols(6);
  while (std::getline(in, line)) {
    const char* p = line.c_str();
    for (auto& c : cols) {
      char* end = nullptr;
      c.push_back(std::strtod(p, &end));
      p = *end == ',' ? end + 1 : end;
    }
  }
  return cols;
}

struct AxisCheck {
  std::string name;
  double chi2_dof = 0, scatter = 0, n = 0, n_ref = 0, b = 0, b_ref = 0;
  int outside = 0, checked = 0, excluded = 0;
  std::vector<double> n_ref_taus;  // the taus of the -1/2-slope run n_ref is the median over
  double worst = 0;  // largest |model/measured - 1| beyond the widened interval
  std::string extras;  // optional terms kept (automatically)
};

AxisCheck check_axis(const std::vector<double>& rate, const std::string& name) {
  const double tau0 = 1.0 / kRateHz;
  const auto phase = phase_from_rate(rate, tau0, 0.0);
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; 2 * m < phase.size(); m *= 2) factors.push_back(m);
  auto curve = oadev(phase, tau0, factors);
  fill_confidence(curve, Estimator::oadev, phase, 0.95);
  fit::FitOptions options;
  // IMUNOISE_FIT_EXACT=1 shows the exact-model fit without the short-tau cut, mismatch scatter
  // and band edge (docs/fit.md's before/after table;
  // the assertions then fail, as they did).
  if (const char* v = std::getenv("IMUNOISE_FIT_EXACT"); v != nullptr && std::atoi(v) != 0) {
    options.model_mismatch = false;
    options.exclude_distorted = false;
    options.flicker_band_edge = false;
  }
  // IMUNOISE_FIT_NO_AUTO=1: the default fit without the automatic optional terms (the state
  // before they were added; docs/fit.md's accelerometer table).
  if (const char* v = std::getenv("IMUNOISE_FIT_NO_AUTO"); v != nullptr && std::atoi(v) != 0) {
    options.auto_extra_terms = false;
  }
  const auto r = fit::fit_allan(curve, phase.size(), tau0, options);
  EXPECT_EQ(r.summary.termination, fit::Termination::converged) << name;
  AxisCheck a;
  a.name = name;
  a.chi2_dof = r.summary.chi2_dof;
  a.scatter = r.summary.mismatch_scatter;
  a.excluded = static_cast<int>(r.summary.excluded_taus.size());
  a.n = r.coefficients.random_walk.value;
  a.b = r.coefficients.bias_instability.value;
  if (r.extras.gauss_markov.selected && !r.coefficients.gauss_markov.empty()) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " GM(Tc %.3g s)", r.coefficients.gauss_markov.front().correlation_time_s.value);
    a.extras += buf;
  }
  if (r.extras.sinusoid.selected && r.coefficients.sinusoid) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " SIN(%.4g Hz)", r.coefficients.sinusoid->frequency_hz.value);
    a.extras += buf;
  }
  double first_fitted = 0.0;
  for (const auto& p : r.residuals) {
    if (p.used) {
      first_fitted = p.tau_s;
      break;
    }
  }
  // Model within the widened measured intervals.
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const auto& p = curve[i];
    if (p.tau_s < 0.1 - 1e-12) continue;
    const auto it = std::find_if(r.residuals.begin(), r.residuals.end(),
                                 [&](const fit::TauResidual& q) { return q.tau_s == p.tau_s; });
    if (it == r.residuals.end()) continue;
    const double model = std::sqrt(it->avar_model);
    ++a.checked;
    const double lo = p.ci_low / 1.15, hi = p.ci_high * 1.15;
    if (model < lo || model > hi) {
      ++a.outside;
      a.worst = std::max(a.worst, std::abs(model / p.dev - 1.0));
      std::printf("  %s: tau %g s: model %.5g outside [%.5g, %.5g]\n", name.c_str(), p.tau_s,
                  model, lo, hi);
    }
  }
  // -1/2-slope value of N.
  std::vector<double> nvals;
  for (std::size_t i = 1; i + 1 < curve.size(); ++i) {
    if (curve[i].tau_s < first_fitted) continue;
    const double s = std::log(curve[i + 1].dev / curve[i - 1].dev) /
                     std::log(curve[i + 1].tau_s / curve[i - 1].tau_s);
    if (std::abs(s + 0.5) <= 0.1) {
      nvals.push_back(curve[i].dev * std::sqrt(curve[i].tau_s));
      a.n_ref_taus.push_back(curve[i].tau_s);
    } else if (!nvals.empty()) {
      break;  // the first -1/2 region only: white noise shows first, after the sampling chain
    }
  }
  if (!nvals.empty()) {
    std::sort(nvals.begin(), nvals.end());
    a.n_ref = nvals.size() % 2 ? nvals[nvals.size() / 2]
                               : 0.5 * (nvals[nvals.size() / 2 - 1] + nvals[nvals.size() / 2]);
  }
  double min_dev = curve[0].dev;
  for (const auto& p : curve) min_dev = std::min(min_dev, p.dev);
  a.b_ref = min_dev / 0.664;
  return a;
}

TEST(RealAdis16405, DefaultFitFollowsEveryAxisOfEveryUnit) {
  const auto files = units();
  if (files.empty()) {
    GTEST_SKIP() << "no adis16405_unit*.csv in " << shared_data()
                 << " (the real recordings live outside the repository; set "
                    "IMUNOISE_SHARED_DATA to their folder)";
  }
  for (const auto& file : files) {
    const auto cols = read_columns(file);
    ASSERT_GT(cols[0].size(), 100000u) << file;
    std::printf("\n%s\n%-12s %9s %8s %4s %11s %11s %6s %11s %11s %6s %s\n",
                file.filename().string().c_str(), "axis", "chi2/dof", "scatter", "excl", "N",
                "N(-1/2)", "ratio", "B", "min/0.664", "ratio", "outside");
    for (const int c : axes()) {
      const auto a = check_axis(cols[static_cast<std::size_t>(c)], kColumns[c]);
      std::printf("%-12s %9.3g %7.2f%% %4d %11.5g %11.5g %6.3f %11.5g %11.5g %6.3f %d/%d%s\n",
                  a.name.c_str(), a.chi2_dof, 100 * a.scatter, a.excluded, a.n, a.n_ref,
                  a.n / a.n_ref, a.b, a.b_ref, a.b / a.b_ref, a.outside, a.checked,
                  a.extras.c_str());
      const std::string where = file.filename().string() + " " + a.name;
      EXPECT_TRUE(std::isfinite(a.chi2_dof) && a.chi2_dof > 0) << where;
      EXPECT_GT(a.checked, 8) << where;
      ASSERT_GT(a.n_ref, 0) << where << ": no -1/2 slope region";
      EXPECT_NEAR(a.n / a.n_ref, 1.0, 0.10) << where << ": N";
      EXPECT_GE(a.b / a.b_ref, 0.6) << where << ": B";
      EXPECT_EQ(a.outside, 0) << where << ": model outside the widened 95% intervals";
      EXPECT_LE(a.b / a.b_ref, 1.25) << where << ": B";
    }
  }
}

// GMWM with model selection (--method gmwm --terms auto) on the same axes, with criteria from
// the record alone: the fit converges; the model's white-noise level where the curve shows it
// (sigma(tau) sqrt(tau) of the fitted model, median over the taus of the -1/2-slope run) within
// 10 % of the measured one. Not the N term alone: a GM term faster than those taus is white
// noise there (2 sigma^2 T_c adds to N^2), and gmwm's N is the rest -- on other units 0.89-0.90
// of the -1/2-slope value with N+GM+GM models. And the model's wavelet variance within the
// measured 95 % interval (+-1.96 sd, no widening) at all but at most 3 of the ~16 dyadic scales
// (for a correct model each scale falls outside with probability 0.05: 3 or fewer of 16 has
// probability 0.96) -- or, where it is not, the J test rejects the model (p < 1e-3), so the
// tool says so: on the accelerometers of units 1, 3, 5 and 6 (a line at 0.47-0.58 Hz from the
// test setup on every unit and GM sums leave correlated residuals; docs/fit.md).
TEST(RealAdis16405, GmwmAutoFollowsEveryAxisOfEveryUnit) {
  const auto files = units();
  if (files.empty()) {
    GTEST_SKIP() << "no adis16405_unit*.csv in " << shared_data()
                 << " (the real recordings live outside the repository; set "
                    "IMUNOISE_SHARED_DATA to their folder)";
  }
  const double tau0 = 1.0 / kRateHz;
  for (const auto& file : files) {
    const auto cols = read_columns(file);
    std::printf("\n%s (gmwm auto)\n%-12s %-22s %8s %4s %7s %11s %11s %11s %s\n", file.filename().string().c_str(), "axis",
                "model", "J", "dof", "p", "N", "model(-1/2)", "N(-1/2)", "outside");
    for (const int c : axes()) {
      const std::string where = file.filename().string() + " " + kColumns[c];
      const auto& rate = cols[static_cast<std::size_t>(c)];
      const auto slope = check_axis(rate, kColumns[c]);  // the -1/2-slope N of the same curve
      const auto phase = phase_from_rate(rate, tau0, compensated_mean(rate));
      std::vector<std::size_t> factors;
      for (std::size_t m = 1; 2 * m < phase.size(); m *= 2) factors.push_back(m);
      auto curve = oadev(phase, tau0, factors);
      fill_confidence(curve, Estimator::oadev, phase, 0.95);
      fit::FitOptions options;
      options.method = fit::Method::gmwm;
      options.gmwm.automatic = true;
      const auto r = fit::fit_allan(curve, phase.size(), tau0, options);
      ASSERT_TRUE(r.gmwm.has_value()) << where;
      const auto& g = *r.gmwm;
      EXPECT_EQ(g.status, fit::GmwmStatus::converged) << where << ": " << g.message;
      int outside = 0;
      for (const auto& scale : g.scales) {
        if (std::abs(scale.wv - scale.wv_model) > 1.96 * scale.wv_sd) ++outside;
      }
      double n = 0.0;
      for (const auto& t : g.terms) {
        if (t.kind == fit::GmwmTerm::N) n = t.magnitude.value;
      }
      std::vector<double> white;
      for (const double tau : slope.n_ref_taus) {
        const auto m = static_cast<std::size_t>(std::llround(tau / tau0));
        white.push_back(std::sqrt(fit::gmwm_model_avar(g, tau0, m) * tau));
      }
      std::sort(white.begin(), white.end());
      const double n_model = white.empty() ? 0.0
                             : white.size() % 2 ? white[white.size() / 2]
                                                : 0.5 * (white[white.size() / 2 - 1] + white[white.size() / 2]);
      std::printf("%-12s %-22s %8.1f %4zu %7.2g %11.5g %11.5g %11.5g %d/%zu\n", kColumns[c], g.model.c_str(),
                  g.j_statistic, g.dof, g.j_p_value, n, n_model, slope.n_ref, outside, g.scales.size());
      EXPECT_GE(g.scales.size(), 12u) << where;
      ASSERT_FALSE(white.empty()) << where << ": no -1/2 slope region";
      EXPECT_NEAR(n_model / slope.n_ref, 1.0, 0.10) << where << ": the model's white-noise level";
      EXPECT_GT(n, 0.0) << where << ": N not identified";
      if (outside > 3) {
        EXPECT_LT(g.j_p_value, 1e-3) << where << ": model outside the measured 95 % intervals, J does not say so";
      }
    }
  }
}

}  // namespace
