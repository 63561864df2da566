#include "imunoise/sim/describe.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <iterator>
#include <numbers>
#include <vector>

#include <fmt/format.h>

namespace imunoise::sim {
namespace {

// Unit names of each coefficient for a rate unit U ("deg/s" -> Q in deg, N in deg/sqrt(s)).
struct CoefficientUnits {
  std::string q, n, b, k, r;
};

CoefficientUnits coefficient_units(const std::string& u) {
  const bool per_second = u.size() > 2 && u.ends_with("/s");
  const std::string base = per_second ? u.substr(0, u.size() - 2) : "(" + u + ")*s";
  return {base, per_second ? base + "/sqrt(s)" : "(" + u + ")*sqrt(s)", u, u + "/sqrt(s)", u + "/s"};
}

}  // namespace

// Customary gyro units (references.md): deg/sqrt(h), deg/h, deg/h/sqrt(h), deg/h^2, arcsec.
std::string customary_coefficients(const NoiseModel& m, const Unit& unit) {
  if (unit.quantity != Quantity::angular_rate) return "";
  const double deg = unit.to_si * 180.0 / std::numbers::pi;  // deg/s per unit
  std::string out;
  auto add = [&](double v, double factor, const char* name) {
    if (v != 0.0) out += fmt::format("{}{:.6g} {}", out.empty() ? "" : ", ", v * deg * factor, name);
  };
  add(m.q_unit_s, 3600.0, "arcsec");
  add(m.n_unit_sqrt_s, 60.0, "deg/sqrt(h)");
  add(m.b_unit, 3600.0, "deg/h");
  add(m.k_unit_per_sqrt_s, 216000.0, "deg/h/sqrt(h)");
  add(m.r_unit_per_s, 1.296e7, "deg/h^2");
  return out;
}

std::string describe_channel(const ChannelGenerator& g, const std::string& u) {
  const NoiseModel& m = g.model();
  const CoefficientUnits cu = coefficient_units(u);
  std::string s;
  auto add = [&](const std::string& text) { s += (s.empty() ? "" : ", ") + text; };
  if (m.q_unit_s != 0.0) add(fmt::format("Q {:g} {}", m.q_unit_s, cu.q));
  if (m.n_unit_sqrt_s != 0.0) add(fmt::format("N {:g} {}", m.n_unit_sqrt_s, cu.n));
  if (m.b_unit != 0.0) {
    add(fmt::format("B {:g} {} (flicker floor {:g} {} honoured within 0.1% on [{:g}, {:g}] s, {} poles)",
                    m.b_unit, cu.b, kFlickerFloorPerB * m.b_unit, u, m.flicker_tau_min_s,
                    m.flicker_tau_max_s, g.flicker_bank().poles.size()));
  }
  if (m.k_unit_per_sqrt_s != 0.0) add(fmt::format("K {:g} {}", m.k_unit_per_sqrt_s, cu.k));
  if (m.r_unit_per_s != 0.0) add(fmt::format("R {:g} {}", m.r_unit_per_s, cu.r));
  if (m.gm_sigma_unit != 0.0) {
    add(fmt::format("Gauss-Markov sigma {:g} {} tau {:g} s", m.gm_sigma_unit, u, m.gm_time_s));
  }
  if (m.sine_amplitude_unit != 0.0) {
    add(fmt::format("sine {:g} {} at {:g} Hz phase {:g} rad", m.sine_amplitude_unit, u,
                    m.sine_frequency_hz, m.sine_phase_rad));
  }
  if (m.bias_unit != 0.0) add(fmt::format("bias {:g} {}", m.bias_unit, u));
  if (s.empty()) s = "no noise";
  const OutputStage& o = g.output();
  if (std::isfinite(o.range_unit)) s += fmt::format("; saturation at +-{:g} {}", o.range_unit, u);
  if (o.scale_factor != 1.0 || o.offset_output != 0.0) {
    s += fmt::format("; output = {:g} * rate + {:g}", o.scale_factor, o.offset_output);
  }
  if (o.lsb_output > 0.0) s += fmt::format("; ADC step {:g}", o.lsb_output);
  return s;
}

std::string simulation_header(const Generator& generator, const std::string& preset, std::uint64_t seed,
                              const std::string& unit, const std::string& output_unit,
                              const std::string& format) {
  const std::size_t channels = generator.channel_count();
  std::string header;
  header += "# imunoise simulate 0.1.0: synthetic sensor output" +
            (preset.empty() ? std::string() : " (preset " + preset + ")") + "\n";
  header += fmt::format("# rate_hz {:g}  tau0_s {:g}  samples {}  duration_s {:g}  channels {}  seed {}\n",
                        generator.rate_hz(), generator.tau0_s(), generator.sample_count(),
                        static_cast<double>(generator.sample_count()) / generator.rate_hz(), channels, seed);
  header += fmt::format("# unit {} (noise parameters); output unit {}; format {}\n", unit, output_unit, format);
  header += "# sample k = average rate over [k tau0, (k+1) tau0); generator xoshiro256** + ziggurat, "
            "reproducible bit for bit from the seed\n";
  const Unit parsed = parse_unit(unit);
  for (std::size_t c = 0; c < channels; ++c) {
    header += fmt::format("# {}: {}\n", generator.channel_name(c), describe_channel(generator.channel(c), unit));
    const std::string cust = customary_coefficients(generator.channel(c).model(), parsed);
    if (!cust.empty()) header += fmt::format("#   customary: {}\n", cust);
  }
  return header;
}

namespace {

template <class T>
void append_little_endian(std::vector<unsigned char>& out, T value) {
  auto bits = std::bit_cast<std::array<unsigned char, sizeof(T)>>(value);
  if constexpr (std::endian::native == std::endian::big) std::reverse(bits.begin(), bits.end());
  out.insert(out.end(), bits.begin(), bits.end());
}

}  // namespace

void write_samples(Generator& generator, SampleFormat format, unsigned threads,
                   const std::function<void(const void* data, std::size_t bytes)>& write) {
  constexpr std::size_t kFrames = 16384;
  const std::size_t channels = generator.channel_count();
  std::vector<double> chunk(kFrames * channels);
  fmt::memory_buffer text_buffer;
  std::vector<unsigned char> bytes;
  while (const std::size_t frames = generator.generate_interleaved(chunk, threads)) {
    const std::size_t values = frames * channels;
    if (format == SampleFormat::text) {
      text_buffer.clear();
      for (std::size_t k = 0; k < frames; ++k) {
        for (std::size_t c = 0; c < channels; ++c) {
          // Shortest representation that reads back to the same double.
          fmt::format_to(std::back_inserter(text_buffer), "{}", chunk[k * channels + c]);
          text_buffer.push_back(c + 1 < channels ? '\t' : '\n');
        }
      }
      write(text_buffer.data(), text_buffer.size());
    } else {
      bytes.clear();
      for (std::size_t i = 0; i < values; ++i) {
        if (format == SampleFormat::f64) {
          append_little_endian(bytes, chunk[i]);
        } else {
          append_little_endian(bytes, static_cast<float>(chunk[i]));
        }
      }
      write(bytes.data(), bytes.size());
    }
  }
}

}  // namespace imunoise::sim
