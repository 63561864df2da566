// Parametric bootstrap of the GMWM fit: records simulated from the fitted model by src/sim.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

#include "imunoise/allan.hpp"
#include "imunoise/sim/generator.hpp"
#include "gmwm_detail.hpp"

namespace imunoise::fit::detail {
namespace {

/// The simulator's Gauss-Markov term is the integrating (sample-averaged) process; the GMWM
/// term is the AR1 of the samples. AR1(s^2, T) = averaged GM(sigma^2, T) + white noise, with
/// sigma^2 = s^2 x^2 / (4 sinh^2(x/2)) and the white part's per-sample variance
/// s^2 [1 - (x - 1 + e^-x) / (2 sinh^2(x/2))] >= 0 (x = tau0 / T; gmwm.hpp): exact.
struct Ar1AsSim {
  double sigma = 0.0;
  double white_per_sample_variance = 0.0;
};
Ar1AsSim ar1_as_sim(double variance, double tc_s, double tau0_s) {
  const double x = tau0_s / tc_s;
  const double sh = std::sinh(0.5 * x);
  Ar1AsSim out;
  out.sigma = std::sqrt(variance * x * x / (4.0 * sh * sh));
  // x - 1 + e^-x by its series for small x (it cancels).
  double e = 0.0;
  if (x < 1e-2) {
    e = x * x / 2.0 - x * x * x / 6.0 + x * x * x * x / 24.0;
  } else {
    e = x - 1.0 + std::exp(-x);
  }
  out.white_per_sample_variance = std::max(0.0, variance * (1.0 - e / (2.0 * sh * sh)));
  return out;
}

struct SimPlan {
  std::vector<sim::ChannelSpec> channels;  // summed
};

SimPlan plan_for(const Layout& layout, const Vector& p, const GmwmCurve& c) {
  const double tau0_s = c.tau0_s;
  sim::NoiseModel main;
  std::vector<sim::NoiseModel> extra;
  double white_variance_rate = 0.0;  // N^2
  bool main_gm_used = false;
  // One AR1 of the samples (variance, T_c) as the simulator's averaged GM plus white noise.
  auto add_ar1 = [&](double v, double tc) {
    const Ar1AsSim s = ar1_as_sim(v, tc, tau0_s);
    white_variance_rate += s.white_per_sample_variance * tau0_s;
    if (!main_gm_used) {
      main.gm_sigma_unit = s.sigma;
      main.gm_time_s = tc;
      main_gm_used = true;
    } else {
      sim::NoiseModel only;
      only.gm_sigma_unit = s.sigma;
      only.gm_time_s = tc;
      extra.push_back(only);
    }
  };
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    const double v = std::exp(p(layout.magnitude[t]));
    switch (layout.terms[t]) {
      case GmwmTerm::Q: main.q_unit_s = std::sqrt(v); break;
      case GmwmTerm::N: white_variance_rate += v; break;
      case GmwmTerm::B: main.b_unit = std::sqrt(v); break;
      case GmwmTerm::K: main.k_unit_per_sqrt_s = std::sqrt(v); break;
      case GmwmTerm::R: main.r_unit_per_s = std::sqrt(v); break;
      case GmwmTerm::SIN:
        main.sine_amplitude_unit = std::sqrt(v);
        main.sine_frequency_hz = std::exp(p(layout.shape[t]));
        break;
      case GmwmTerm::GM: add_ar1(v, std::exp(p(layout.shape[t]))); break;
      case GmwmTerm::BGM:
        // The mixture's states, each an AR1 of the samples (exactly the model fitted).
        for (std::size_t q = 0; q < c.flicker_mixture.correlation_time_s.size(); ++q) {
          add_ar1(v * c.flicker_mixture.variance_per_b2[q], c.flicker_mixture.correlation_time_s[q]);
        }
        break;
    }
  }
  main.n_unit_sqrt_s = std::sqrt(white_variance_rate);
  SimPlan plan;
  plan.channels.push_back({main, {}, "main"});
  for (auto& e : extra) plan.channels.push_back({e, {}, "gm"});
  return plan;
}

}  // namespace

std::vector<Vector> bootstrap_parameters(const Layout& layout, const Vector& p, const GmwmCurve& c,
                                         const Matrix& whiten, int replicates, std::uint64_t seed,
                                         unsigned threads) {
  const SimPlan plan = plan_for(layout, p, c);
  const std::size_t n_samples = c.n_phase - 1;
  const double rate_hz = 1.0 / c.tau0_s;
  const double duration_s = static_cast<double>(n_samples) * c.tau0_s;
  const Bounds bounds = bounds_for(layout, c);
  std::vector<Vector> rows(static_cast<std::size_t>(replicates));
  std::vector<char> ok(static_cast<std::size_t>(replicates), 0);
  unsigned workers = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
  workers = std::min<unsigned>(workers, static_cast<unsigned>(replicates));
  auto work = [&](unsigned w) {
    std::vector<double> rate(n_samples), part(n_samples), phase(c.n_phase);
    for (int r = static_cast<int>(w); r < replicates; r += static_cast<int>(workers)) {
      // Each replicate's streams depend on (seed, replicate) only: not on the thread count.
      const std::uint64_t rseed = seed * 1000003ULL + static_cast<std::uint64_t>(r);
      std::fill(rate.begin(), rate.end(), 0.0);
      for (std::size_t ch = 0; ch < plan.channels.size(); ++ch) {
        sim::ChannelSpec spec = plan.channels[ch];
        if (spec.noise.sine_amplitude_unit > 0.0) {
          spec.noise.sine_phase_rad = 2.0 * std::numbers::pi * static_cast<double>((rseed * 2654435761ULL) % 1000) / 1000.0;
        }
        sim::ChannelGenerator gen(spec, rate_hz, duration_s, rseed, ch);
        gen.generate(part);
        for (std::size_t i = 0; i < n_samples; ++i) rate[i] += part[i];
      }
      double mean = 0.0;
      for (double v : rate) mean += v;
      mean /= static_cast<double>(n_samples);
      phase[0] = 0.0;
      long double acc = 0.0L;
      for (std::size_t i = 0; i < n_samples; ++i) {
        acc += static_cast<long double>((rate[i] - mean) * c.tau0_s);
        phase[i + 1] = static_cast<double>(acc);
      }
      GmwmCurve rc = c;
      bool finite = true;
      if (c.robust) {
        // The robust fit's replicates take the same robust estimates.
        rc.avar = robust_avar(phase, c.tau0_s, c.m, c.biweight);
      } else {
        DevOptions dev;
        dev.threads = 1;
        const auto points = oadev(phase, c.tau0_s, c.m, dev);
        finite = points.size() == c.m.size();
        for (std::size_t i = 0; finite && i < points.size(); ++i) rc.avar[i] = points[i].dev * points[i].dev;
      }
      for (std::size_t i = 0; finite && i < rc.avar.size(); ++i) {
        finite = std::isfinite(rc.avar[i]) && rc.avar[i] > 0.0;
      }
      if (!finite) continue;
      const LmResult lm = levenberg_marquardt(layout, rc, whiten, p, bounds, 200);
      if (std::isfinite(lm.cost)) {
        rows[static_cast<std::size_t>(r)] = lm.p;
        ok[static_cast<std::size_t>(r)] = 1;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (auto& t : pool) t.join();
  std::vector<Vector> out;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (ok[r]) out.push_back(rows[r]);
  }
  return out;
}

}  // namespace imunoise::fit::detail
