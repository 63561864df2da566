#include "deterministic_fp.hpp"  // first: no fused multiply-add in this file

#include "imunoise/sim/generator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <thread>

#include "imunoise/error.hpp"
#include "imunoise/sim/portable_math.hpp"

namespace imunoise::sim {
namespace {

constexpr std::size_t kBlock = 512;  // samples per internal block (normals scratch stays in L2)

NormalGenerator stream(std::uint64_t seed, std::uint64_t channel, TermStream term) {
  return NormalGenerator(make_stream(seed, channel, static_cast<std::uint64_t>(term)));
}

}  // namespace

ChannelGenerator::ChannelGenerator(const ChannelSpec& spec, double rate_hz, double duration_s,
                                   std::uint64_t seed, std::uint64_t channel_index)
    : model_(spec.noise),
      output_(spec.output),
      tau0_s_(0.0),
      q_normals_(stream(seed, channel_index, TermStream::quantization)),
      white_normals_(stream(seed, channel_index, TermStream::white)),
      flicker_normals_(stream(seed, channel_index, TermStream::flicker)),
      rrw_normals_(stream(seed, channel_index, TermStream::rate_random_walk)),
      gm_normals_(stream(seed, channel_index, TermStream::gauss_markov)) {
  validate(model_);
  validate(output_);
  check_sampling(model_, rate_hz, duration_s);
  model_ = resolve_flicker_range(model_, rate_hz, duration_s);
  tau0_s_ = 1.0 / rate_hz;
  const double h = tau0_s_;

  // Q: white angle noise e_k of std Q at the sample instants; sample k = (e_{k+1} - e_k)/tau0.
  if (model_.q_unit_s > 0.0) q_previous_ = model_.q_unit_s * q_normals_();
  // N: the average of white noise of PSD N^2 over tau0 has std N / sqrt(tau0).
  white_per_sample_ = model_.n_unit_sqrt_s / std::sqrt(h);
  // K: rate = K W(t), W(0) = 0. Over one interval, with z1, z2 ~ N(0,1) independent,
  // W increment = sqrt(h) z1 and the interval average of W - W_start = sqrt(h) (z1/2 + z2/sqrt(12)).
  rrw_half_ = model_.k_unit_per_sqrt_s * std::sqrt(h) * 0.5;
  rrw_bridge_ = model_.k_unit_per_sqrt_s * std::sqrt(h) / std::sqrt(12.0);
  // Gauss-Markov: exact update, stationary start.
  if (model_.gm_sigma_unit > 0.0) {
    gm_step_ = gauss_markov_step(model_.gm_sigma_unit, model_.gm_time_s, h);
    gm_state_ = model_.gm_sigma_unit * gm_normals_();
  }
  // Flicker bank: each pole's exact update; the poles' independent parts (their z2) and the
  // low-end white correction are merged into one variate per sample.
  if (model_.b_unit > 0.0) {
    bank_ = design_flicker_bank(model_.b_unit, model_.flicker_tau_min_s, model_.flicker_tau_max_s);
    double residual_variance = bank_.white_n_unit_sqrt_s * bank_.white_n_unit_sqrt_s / h;
    for (const auto& pole : bank_.poles) {
      const GaussMarkovStep st = gauss_markov_step(pole.sigma_unit, pole.time_s, h);
      pole_phi_.push_back(st.phi);
      pole_noise_.push_back(st.state_noise);
      pole_a_.push_back(st.mean_of_state);
      pole_b_.push_back(st.mean_of_z1);
      residual_variance += st.mean_of_z2 * st.mean_of_z2;
    }
    flicker_residual_ = std::sqrt(residual_variance);
    pole_states_.resize(bank_.poles.size());
    for (std::size_t i = 0; i < pole_states_.size(); ++i) {
      pole_states_[i] = bank_.poles[i].sigma_unit * flicker_normals_();
    }
  } else {
    bank_.tau_min_s = model_.flicker_tau_min_s;
    bank_.tau_max_s = model_.flicker_tau_max_s;
  }
  // Sinusoid averaged over each interval: A sinc(pi f h) sin(2 pi (f h (k + 1/2)) + phase).
  if (model_.sine_amplitude_unit > 0.0) {
    const double fh = model_.sine_frequency_hz * h;
    const double x = std::numbers::pi * fh;
    const double sinc = x == 0.0 ? 1.0 : portable::sincos_cycles(0.5 * fh).first / x;
    sine_gain_ = model_.sine_amplitude_unit * sinc;
    sine_cycles_per_sample_ = fh;
    sine_cycles0_ = model_.sine_phase_rad / (2.0 * std::numbers::pi);
  }
}

void ChannelGenerator::generate(std::span<double> out) {
  while (!out.empty()) {
    const std::size_t n = std::min(out.size(), kBlock);
    const std::span<double> y = out.first(n);
    std::fill(y.begin(), y.end(), 0.0);
    add_terms(y);
    apply_output_stage(y);
    index_ += n;
    out = out.subspan(n);
  }
}

void ChannelGenerator::add_terms(std::span<double> y) {
  const std::size_t n = y.size();
  const NoiseModel& m = model_;

  if (m.q_unit_s > 0.0) {
    normals_.resize(n);
    q_normals_.fill(normals_);
    const double q = m.q_unit_s;
    const double inv_h = 1.0 / tau0_s_;
    double previous = q_previous_;
    for (std::size_t k = 0; k < n; ++k) {
      const double e = q * normals_[k];
      y[k] += (e - previous) * inv_h;
      previous = e;
    }
    q_previous_ = previous;
  }

  if (m.n_unit_sqrt_s > 0.0) {
    normals_.resize(n);
    white_normals_.fill(normals_);
    const double s = white_per_sample_;
    for (std::size_t k = 0; k < n; ++k) y[k] += s * normals_[k];
  }

  if (m.b_unit > 0.0) {
    const std::size_t poles = pole_states_.size();
    const std::size_t stride = poles + 1;
    normals_.resize(n * stride);
    flicker_normals_.fill(normals_);
    const double residual = flicker_residual_;
    double* w = pole_states_.data();
    const double* phi = pole_phi_.data();
    const double* noise = pole_noise_.data();
    const double* a = pole_a_.data();
    const double* b = pole_b_.data();
    for (std::size_t k = 0; k < n; ++k) {
      const double* z = normals_.data() + k * stride;
      // Even poles accumulate in one sum, odd poles in another (a fixed order, hence
      // deterministic; two independent chains, which the compiler can pair in one register).
      double even = residual * z[poles];
      double odd = 0.0;
      std::size_t i = 0;
      for (; i + 1 < poles; i += 2) {
        even += a[i] * w[i] + b[i] * z[i];
        odd += a[i + 1] * w[i + 1] + b[i + 1] * z[i + 1];
        w[i] = phi[i] * w[i] + noise[i] * z[i];
        w[i + 1] = phi[i + 1] * w[i + 1] + noise[i + 1] * z[i + 1];
      }
      if (i < poles) {
        even += a[i] * w[i] + b[i] * z[i];
        w[i] = phi[i] * w[i] + noise[i] * z[i];
      }
      y[k] += even + odd;
    }
  }

  if (m.k_unit_per_sqrt_s > 0.0) {
    normals_.resize(2 * n);
    rrw_normals_.fill(normals_);
    double rate = rrw_rate_;
    const double half = rrw_half_;
    const double bridge = rrw_bridge_;
    const double step = 2.0 * half;
    for (std::size_t k = 0; k < n; ++k) {
      const double z1 = normals_[2 * k];
      const double z2 = normals_[2 * k + 1];
      y[k] += rate + (half * z1 + bridge * z2);
      rate += step * z1;
    }
    rrw_rate_ = rate;
  }

  if (m.r_unit_per_s != 0.0) {
    const double r = m.r_unit_per_s * tau0_s_;
    for (std::size_t k = 0; k < n; ++k) {
      y[k] += r * (static_cast<double>(index_ + k) + 0.5);
    }
  }

  if (m.gm_sigma_unit > 0.0) {
    normals_.resize(2 * n);
    gm_normals_.fill(normals_);
    const GaussMarkovStep st = gm_step_;
    double w = gm_state_;
    for (std::size_t k = 0; k < n; ++k) {
      const double z1 = normals_[2 * k];
      const double z2 = normals_[2 * k + 1];
      y[k] += st.mean_of_state * w + (st.mean_of_z1 * z1 + st.mean_of_z2 * z2);
      w = st.phi * w + st.state_noise * z1;
    }
    gm_state_ = w;
  }

  if (m.sine_amplitude_unit > 0.0) {
    for (std::size_t k = 0; k < n; ++k) {
      const double cycles =
          sine_cycles_per_sample_ * (static_cast<double>(index_ + k) + 0.5) + sine_cycles0_;
      y[k] += sine_gain_ * portable::sincos_cycles(cycles).first;
    }
  }

  if (m.bias_unit != 0.0) {
    for (double& v : y) v += m.bias_unit;
  }
}

void ChannelGenerator::apply_output_stage(std::span<double> y) const {
  const OutputStage& o = output_;
  if (std::isfinite(o.range_unit)) {
    for (double& v : y) v = std::clamp(v, -o.range_unit, o.range_unit);
  }
  if (o.scale_factor != 1.0 || o.offset_output != 0.0) {
    for (double& v : y) v = o.scale_factor * v + o.offset_output;
  }
  if (o.lsb_output > 0.0) {
    const double lsb = o.lsb_output;
    for (double& v : y) v = lsb * std::nearbyint(v / lsb);
  }
}

Generator::Generator(const SimulationSpec& spec) : rate_hz_(spec.rate_hz), sample_count_(0) {
  if (spec.channels.empty()) throw InputError("the simulation has no channel");
  channels_.reserve(spec.channels.size());
  for (std::size_t c = 0; c < spec.channels.size(); ++c) {
    const std::string name = spec.channels[c].name.empty() ? "ch" + std::to_string(c + 1)
                                                           : spec.channels[c].name;
    try {
      channels_.emplace_back(spec.channels[c], spec.rate_hz, spec.duration_s, spec.seed, c);
    } catch (const InputError& e) {
      throw InputError(spec.channels.size() > 1 ? "channel " + name + ": " + e.what() : e.what());
    }
    names_.push_back(name);
  }
  sample_count_ = static_cast<std::uint64_t>(std::llround(spec.duration_s * spec.rate_hz));
}

std::size_t Generator::generate_planar(std::span<const std::span<double>> out, unsigned threads) {
  if (out.size() != channels_.size()) {
    throw InputError("generate_planar: got " + std::to_string(out.size()) + " buffers for " +
                     std::to_string(channels_.size()) + " channels");
  }
  std::size_t n = out.front().size();
  for (const auto& buffer : out) n = std::min(n, buffer.size());
  n = static_cast<std::size_t>(std::min<std::uint64_t>(n, remaining()));
  if (n == 0) return 0;
  const std::size_t workers = std::min<std::size_t>(std::max(1U, threads), channels_.size());
  if (workers <= 1) {
    for (std::size_t c = 0; c < channels_.size(); ++c) channels_[c].generate(out[c].first(n));
  } else {
    std::vector<std::jthread> pool;
    pool.reserve(workers);
    for (std::size_t w = 0; w < workers; ++w) {
      pool.emplace_back([this, &out, n, w, workers] {
        for (std::size_t c = w; c < channels_.size(); c += workers) channels_[c].generate(out[c].first(n));
      });
    }
  }
  position_ += n;
  return n;
}

std::size_t Generator::generate_interleaved(std::span<double> out, unsigned threads) {
  const std::size_t channels = channels_.size();
  if (out.size() % channels != 0) {
    throw InputError("generate_interleaved: buffer size " + std::to_string(out.size()) +
                     " is not a multiple of the channel count " + std::to_string(channels));
  }
  const std::size_t frames =
      static_cast<std::size_t>(std::min<std::uint64_t>(out.size() / channels, remaining()));
  if (frames == 0) return 0;
  scratch_.resize(frames * channels);
  std::vector<std::span<double>> planes;
  planes.reserve(channels);
  for (std::size_t c = 0; c < channels; ++c) {
    planes.push_back(std::span<double>(scratch_).subspan(c * frames, frames));
  }
  generate_planar(planes, threads);
  for (std::size_t k = 0; k < frames; ++k) {
    for (std::size_t c = 0; c < channels; ++c) out[k * channels + c] = planes[c][k];
  }
  return frames;
}

std::vector<double> simulate(const ChannelSpec& spec, double rate_hz, std::size_t n_samples,
                             std::uint64_t seed, std::uint64_t channel_index) {
  const double duration = static_cast<double>(n_samples) / rate_hz;
  ChannelGenerator generator(spec, rate_hz, duration, seed, channel_index);
  std::vector<double> out(n_samples);
  generator.generate(out);
  return out;
}

std::vector<double> simulate(const NoiseModel& model, double rate_hz, std::size_t n_samples,
                             std::uint64_t seed, std::uint64_t channel_index) {
  ChannelSpec spec;
  spec.noise = model;
  return simulate(spec, rate_hz, n_samples, seed, channel_index);
}

}  // namespace imunoise::sim
