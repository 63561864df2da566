// Monte Carlo: the nav error states driven by simulated gyro and accelerometer samples, many
// seeded runs.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <thread>

#include <fmt/core.h>

#include "error_model.hpp"
#include "imunoise/nav/models.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/sim/rng.hpp"

namespace imunoise::nav {
namespace {

// Blocks of runs are the unit of work and of merging (in block order), so the sums, hence the
// result, are the same for any thread count. At least 16 runs a block, and at most 1024 blocks
// (bounded memory for the per-block sums); the size depends on the run count only.
std::size_t block_runs(std::size_t runs) { return std::max<std::size_t>(16, (runs + 1023) / 1024); }
constexpr std::size_t kChunk = 2048;

// Per reported time: sums over runs of x, x^2, x^4 for both channels and of r^4, r^2 = N^2 + E^2.
struct Sums {
  explicit Sums(std::size_t times)
      : n1(times), n2(times), n4(times), e1(times), e2(times), e4(times), r4(times) {}
  std::vector<double> n1, n2, n4, e1, e2, e4, r4;
  void add(std::size_t i, double n, double e) {
    const double nn = n * n, ee = e * e;
    n1[i] += n;
    n2[i] += nn;
    n4[i] += nn * nn;
    e1[i] += e;
    e2[i] += ee;
    e4[i] += ee * ee;
    r4[i] += (nn + ee) * (nn + ee);
  }
  void merge(const Sums& o) {
    for (std::size_t i = 0; i < n1.size(); ++i) {
      n1[i] += o.n1[i];
      n2[i] += o.n2[i];
      n4[i] += o.n4[i];
      e1[i] += o.e1[i];
      e2[i] += o.e2[i];
      e4[i] += o.e4[i];
      r4[i] += o.r4[i];
    }
  }
};

// Channel streams: gyros 0..2, the gyros' random constants 3, accelerometers x y 4..5, their
// random constants 6 (so the gyro draws do not change when accelerometers are added).
constexpr std::uint64_t kGyroConstants = 3;
constexpr std::uint64_t kAccelChannel0 = 4;
constexpr std::uint64_t kAccelConstants = 6;

sim::ChannelSpec channel_of(const detail::SensorTerms& t, const detail::FlickerRange& range) {
  sim::ChannelSpec c;
  sim::NoiseModel& m = c.noise;  // in rad/s or m/s^2: the simulator is unit-agnostic
  m.q_unit_s = t.q;
  m.n_unit_sqrt_s = t.n;
  m.b_unit = t.b;
  m.k_unit_per_sqrt_s = t.k;
  m.r_unit_per_s = t.r;
  // The simulator's channel has one Gauss-Markov process: the first term here, the others in
  // gauss_markov_channels (summed).
  if (!t.gauss_markov.empty()) {
    m.gm_sigma_unit = t.gauss_markov.front().sigma;
    m.gm_time_s = t.gauss_markov.front().time_s;
  }
  m.bias_unit = t.bias;
  m.flicker_tau_min_s = range.tau_min_s;
  m.flicker_tau_max_s = range.tau_max_s;
  return c;
}

// One channel per Gauss-Markov term after the first, added to the sensor's samples. Stream
// 8 g + sensor for the g-th extra term (g >= 1): disjoint from the channels 0..6 above.
struct ExtraChannel {
  sim::ChannelSpec spec;
  std::uint64_t stream = 0;
  int sensor = 0;  // 0..2 gyro x y z, 3..4 accelerometer x y
};

void add_gauss_markov_channels(const detail::SensorTerms& t, int sensor, std::vector<ExtraChannel>& out) {
  for (std::size_t g = 1; g < t.gauss_markov.size(); ++g) {
    ExtraChannel c;
    c.spec.noise.gm_sigma_unit = t.gauss_markov[g].sigma;
    c.spec.noise.gm_time_s = t.gauss_markov[g].time_s;
    c.stream = 8 * static_cast<std::uint64_t>(g) + static_cast<std::uint64_t>(sensor);
    c.sensor = sensor;
    out.push_back(c);
  }
}

std::uint64_t run_seed(std::uint64_t seed, std::size_t run) {
  sim::SplitMix64 mix(seed + static_cast<std::uint64_t>(run) * 0x9e3779b97f4a7c15ULL);
  return mix.next();
}

// One run's channels: the drift and the ramp of each axis as given (signed), or drawn as random
// constants N(0, given^2) from the run's own stream (`constants`, disjoint from the channels').
// Two draws per axis whatever is present, so a run's draws do not depend on the model.
template <std::size_t N>
std::array<sim::ChannelSpec, N> run_specs(const std::array<sim::ChannelSpec, N>& specs, std::uint64_t run_seed,
                                          bool signed_constants, std::uint64_t constants) {
  std::array<sim::ChannelSpec, N> run = specs;
  if (signed_constants) return run;
  sim::NormalGenerator z(sim::make_stream(run_seed, constants, 0));
  for (sim::ChannelSpec& c : run) {
    c.noise.bias_unit *= z();
    c.noise.r_unit_per_s *= z();
  }
  return run;
}

}  // namespace

ModelSeries montecarlo_series(const NavOptions& o, const ImuTerms& terms, const std::vector<double>& t_s) {
  ModelSeries s;
  s.model = Model::montecarlo;
  const detail::FlickerRange range = detail::flicker_range(o);
  const detail::NavStep step = detail::nav_step(o);
  const double rate_hz = 1.0 / o.dt_s;
  std::array<sim::ChannelSpec, 3> specs;
  std::vector<ExtraChannel> extra;
  for (int a = 0; a < 3; ++a) {
    const detail::SensorTerms t = detail::sensor_terms(terms.gyro[static_cast<std::size_t>(a)]);
    specs[static_cast<std::size_t>(a)] = channel_of(t, range);
    add_gauss_markov_channels(t, a, extra);
  }
  // The horizontal accelerometers, simulated only when they have a term.
  std::array<sim::ChannelSpec, 2> accel_specs;
  bool accelerometers = false;
  for (int a = 0; a < 2; ++a) {
    const detail::SensorTerms t = detail::sensor_terms(terms.accel[static_cast<std::size_t>(a)]);
    accel_specs[static_cast<std::size_t>(a)] = channel_of(t, range);
    for (double v : {t.q, t.n, t.b, t.k, t.r, gauss_markov_rss(t.gauss_markov), t.bias}) {
      accelerometers = accelerometers || v != 0.0;
    }
  }
  if (accelerometers) {
    for (int a = 0; a < 2; ++a) {
      add_gauss_markov_channels(detail::sensor_terms(terms.accel[static_cast<std::size_t>(a)]), 3 + a, extra);
    }
  }
  for (const auto& c : extra) sim::ChannelGenerator(c.spec, rate_hz, o.duration_s, o.seed, c.stream);
  // Validate once, up front, where an InputError can still reach the caller directly.
  for (int a = 0; a < 3; ++a) sim::ChannelGenerator(specs[static_cast<std::size_t>(a)], rate_hz, o.duration_s, o.seed, static_cast<std::uint64_t>(a));
  if (accelerometers) {
    for (int a = 0; a < 2; ++a) {
      sim::ChannelGenerator(accel_specs[static_cast<std::size_t>(a)], rate_hz, o.duration_s, o.seed, kAccelChannel0 + static_cast<std::uint64_t>(a));
    }
  }

  std::vector<long> report_step;
  for (double t : t_s) report_step.push_back(std::lround(t / o.dt_s));
  const long total_steps = report_step.back();
  const std::size_t times = t_s.size();
  const std::size_t runs = o.runs;
  const std::size_t kBlockRuns = block_runs(runs);
  const std::size_t blocks = (runs + kBlockRuns - 1) / kBlockRuns;
  std::vector<Sums> block_sums(blocks, Sums(times));

  auto run_block = [&](std::size_t b) {
    Sums& sums = block_sums[b];
    std::array<std::vector<double>, 3> eps;
    for (auto& e : eps) e.resize(kChunk);
    std::array<std::vector<double>, 2> acc;
    for (auto& e : acc) e.resize(accelerometers ? kChunk : 0);
    std::vector<double> part(extra.empty() ? 0 : kChunk);
    for (std::size_t r = b * kBlockRuns; r < std::min(runs, (b + 1) * kBlockRuns); ++r) {
      const std::uint64_t seed = run_seed(o.seed, r);
      const std::array<sim::ChannelSpec, 3> run = run_specs(specs, seed, o.signed_constants, kGyroConstants);
      std::vector<sim::ChannelGenerator> gens;
      gens.reserve(5);
      for (int a = 0; a < 3; ++a) gens.emplace_back(run[static_cast<std::size_t>(a)], rate_hz, o.duration_s, seed, static_cast<std::uint64_t>(a));
      if (accelerometers) {
        const auto accel_run = run_specs(accel_specs, seed, o.signed_constants, kAccelConstants);
        for (int a = 0; a < 2; ++a) {
          gens.emplace_back(accel_run[static_cast<std::size_t>(a)], rate_hz, o.duration_s, seed, kAccelChannel0 + static_cast<std::uint64_t>(a));
        }
      }
      std::vector<sim::ChannelGenerator> extra_gens;
      for (const auto& c : extra) extra_gens.emplace_back(c.spec, rate_hz, o.duration_s, seed, c.stream);
      Eigen::Matrix<double, detail::kNavStates, 1> state = Eigen::Matrix<double, detail::kNavStates, 1>::Zero();
      std::size_t next = 0;
      while (next < times && report_step[next] == 0) sums.add(next++, 0.0, 0.0);
      long k = 0;
      while (k < total_steps) {
        const std::size_t n = static_cast<std::size_t>(std::min<long>(static_cast<long>(kChunk), total_steps - k));
        for (int a = 0; a < 3; ++a) gens[static_cast<std::size_t>(a)].generate(std::span<double>(eps[static_cast<std::size_t>(a)].data(), n));
        if (accelerometers) {
          for (int a = 0; a < 2; ++a) gens[3 + static_cast<std::size_t>(a)].generate(std::span<double>(acc[static_cast<std::size_t>(a)].data(), n));
        }
        for (std::size_t x = 0; x < extra.size(); ++x) {
          extra_gens[x].generate(std::span<double>(part.data(), n));
          const int sensor = extra[x].sensor;
          std::vector<double>& into = sensor < 3 ? eps[static_cast<std::size_t>(sensor)] : acc[static_cast<std::size_t>(sensor - 3)];
          for (std::size_t i = 0; i < n; ++i) into[i] += part[i];
        }
        for (std::size_t i = 0; i < n; ++i) {
          const Eigen::Vector3d e(eps[0][i], eps[1][i], eps[2][i]);
          state = step.phi * state + step.gamma * e;
          if (accelerometers) state += step.accel_gamma * Eigen::Vector2d(acc[0][i], acc[1][i]);
          ++k;
          while (next < times && report_step[next] == k) sums.add(next++, state(0), state(1));
        }
      }
    }
  };

  const unsigned hw = std::max(1U, std::thread::hardware_concurrency());
  const unsigned threads = static_cast<unsigned>(std::min<std::size_t>(o.threads == 0 ? hw : o.threads, blocks));
  std::atomic<std::size_t> next_block{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    try {
      for (std::size_t b; (b = next_block.fetch_add(1)) < blocks;) run_block(b);
    } catch (...) {
      std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);

  Sums total(times);
  for (const Sums& b : block_sums) total.merge(b);

  const double n = static_cast<double>(runs);
  const double r = o.earth.radius_m;
  MonteCarloStats st;
  st.runs = runs;
  st.seed = o.seed;
  const bool at_pole = std::abs(std::cos(o.latitude_rad)) < 1e-12;
  // Standard error of a mean of v from sums of v and v^2 (sample variance / n).
  auto se_of_mean = [n](double sum, double sum_sq) {
    if (n < 2) return 0.0;
    const double mean = sum / n;
    return std::sqrt(std::max(sum_sq / n - mean * mean, 0.0) * n / (n - 1.0) / n);
  };
  for (std::size_t i = 0; i < times; ++i) {
    s.t_s.push_back(t_s[i]);
    const double msn = total.n2[i] / n, mse = total.e2[i] / n;
    const double rmsn = std::sqrt(msn), rmse = std::sqrt(mse), rmsr = std::sqrt(msn + mse);
    s.lat_rad.push_back(rmsn);
    if (!at_pole) s.lon_rad.push_back(rmse / std::abs(std::cos(o.latitude_rad)));
    s.north_m.push_back(r * rmsn);
    s.east_m.push_back(r * rmse);
    s.radial_m.push_back(r * rmsr);
    st.mean_north_m.push_back(r * total.n1[i] / n);
    st.mean_east_m.push_back(r * total.e1[i] / n);
    st.se_mean_north_m.push_back(r * se_of_mean(total.n1[i], total.n2[i]));
    st.se_mean_east_m.push_back(r * se_of_mean(total.e1[i], total.e2[i]));
    // SE of a mean square from the sums of x^2 and x^4; SE of its root by the delta method.
    const double se_msn = se_of_mean(total.n2[i], total.n4[i]);
    const double se_mse = se_of_mean(total.e2[i], total.e4[i]);
    const double se_msr = se_of_mean(total.n2[i] + total.e2[i], total.r4[i]);
    st.ms_north_m2.push_back(r * r * msn);
    st.ms_east_m2.push_back(r * r * mse);
    st.se_ms_north_m2.push_back(r * r * se_msn);
    st.se_ms_east_m2.push_back(r * r * se_mse);
    st.se_rms_north_m.push_back(rmsn > 0 ? r * se_msn / (2 * rmsn) : 0.0);
    st.se_rms_east_m.push_back(rmse > 0 ? r * se_mse / (2 * rmse) : 0.0);
    st.se_rms_radial_m.push_back(rmsr > 0 ? r * se_msr / (2 * rmsr) : 0.0);
  }
  s.montecarlo = std::move(st);
  s.assumptions = fmt::format(
      "the covariance model's nav error states (same F, Earth rate {}) driven by gyro{} samples from the "
      "project's simulator at {:.6g} Hz (each sample the exact average of the continuous noise over dt; the "
      "states see it as piecewise constant); {} runs, seed {} (run r: SplitMix64 of seed + r golden, channel "
      "= axis), any thread count; RMS over runs with standard errors (delta method on the mean square); {}",
      o.earth_rate ? "on" : "off", accelerometers ? " and horizontal accelerometer" : "", rate_hz, runs, o.seed,
      o.signed_constants
          ? "constant drift and ramp as given, signed and the same in every run (--signed-constants), so the "
            "mean is not zero when they are present and drifts on several axes add with their signs"
          : "constant drift and ramp drawn per run and axis as independent random constants with the given "
            "value as standard deviation, as the covariance and Schuler models read them");
  return s;
}

}  // namespace imunoise::nav
