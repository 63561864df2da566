// imunoise simulate: synthetic sensor output with a given noise model (or the paper's preset),
// streamed in chunks to text or raw binary, reproducible bit for bit from its seed.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <fmt/format.h>

#include "commands.hpp"
#include "imunoise/error.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/sim/presets.hpp"
#include "imunoise/units.hpp"

namespace imunoise::cli {
namespace {

struct SimulateOptionsCli {
  double rate_hz = 0.0;
  double duration_s = 21600.0;
  sim::NoiseModel noise;
  double range = std::numeric_limits<double>::infinity();
  double scale_factor = 1.0;
  double volts_per_unit = 0.0;
  double offset = 0.0;
  double lsb = 0.0;
  std::string units = "deg/s";
  std::string preset;
  std::size_t channels = 1;
  std::uint64_t seed = 1;
  std::string format = "text";
  std::string path;
  bool force = false;
  unsigned threads = 0;
  // Options given on the command line (to detect conflicts with --preset).
  std::vector<CLI::Option*> noise_options;
  CLI::Option* rate_option = nullptr;
  CLI::Option* channels_option = nullptr;
  CLI::Option* units_option = nullptr;
  CLI::Option* range_option = nullptr;
};

// Unit names of each coefficient for a rate unit U ("deg/s" -> Q in deg, N in deg/sqrt(s)).
struct CoefficientUnits {
  std::string q, n, b, k, r;
};

CoefficientUnits coefficient_units(const std::string& u) {
  const bool per_second = u.size() > 2 && u.ends_with("/s");
  const std::string base = per_second ? u.substr(0, u.size() - 2) : "(" + u + ")*s";
  return {base, per_second ? base + "/sqrt(s)" : "(" + u + ")*sqrt(s)", u, u + "/sqrt(s)", u + "/s"};
}

// Customary gyro units (references.md): deg/sqrt(h), deg/h, deg/h/sqrt(h), deg/h^2, arcsec.
std::string customary(const sim::NoiseModel& m, const Unit& unit) {
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

std::string describe(const sim::ChannelGenerator& g, const std::string& u) {
  const sim::NoiseModel& m = g.model();
  const CoefficientUnits cu = coefficient_units(u);
  std::string s;
  auto add = [&](const std::string& text) { s += (s.empty() ? "" : ", ") + text; };
  if (m.q_unit_s != 0.0) add(fmt::format("Q {:g} {}", m.q_unit_s, cu.q));
  if (m.n_unit_sqrt_s != 0.0) add(fmt::format("N {:g} {}", m.n_unit_sqrt_s, cu.n));
  if (m.b_unit != 0.0) {
    add(fmt::format("B {:g} {} (flicker floor {:g} {} honoured within 0.1% on [{:g}, {:g}] s, {} poles)",
                    m.b_unit, cu.b, sim::kFlickerFloorPerB * m.b_unit, u, m.flicker_tau_min_s,
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
  const sim::OutputStage& o = g.output();
  if (std::isfinite(o.range_unit)) s += fmt::format("; saturation at +-{:g} {}", o.range_unit, u);
  if (o.scale_factor != 1.0 || o.offset_output != 0.0) {
    s += fmt::format("; output = {:g} * rate + {:g}", o.scale_factor, o.offset_output);
  }
  if (o.lsb_output > 0.0) s += fmt::format("; ADC step {:g}", o.lsb_output);
  return s;
}

// Output that is never silently replaced: a temporary file renamed at the end (like
// write_output), or standard output. Written chunk by chunk.
class Sink {
 public:
  Sink(const std::string& path, bool force) : path_(path) {
    if (path.empty() || path == "-") {
      file_ = stdout;
      return;
    }
    namespace fs = std::filesystem;
    if (fs::exists(path) && !force) {
      throw InputError(path + ": file exists; imunoise does not overwrite it — choose another -o name "
                       "or pass --force");
    }
    temporary_ = path + ".imunoise-tmp";
    file_ = std::fopen(temporary_.c_str(), "wb");
    if (!file_) throw InputError(path + ": cannot create the file; check the directory");
  }
  Sink(const Sink&) = delete;
  Sink& operator=(const Sink&) = delete;
  ~Sink() {
    if (file_ && file_ != stdout) {
      std::fclose(file_);
      std::error_code ignored;
      std::filesystem::remove(temporary_, ignored);  // not committed: leave nothing behind
    }
  }
  void write(const void* data, std::size_t bytes) {
    if (bytes != 0 && std::fwrite(data, 1, bytes, file_) != bytes) {
      throw InputError((file_ == stdout ? std::string("standard output") : path_) +
                       ": write failed (disk full or closed pipe?)");
    }
  }
  void commit() {
    if (file_ == stdout) {
      std::fflush(stdout);
      return;
    }
    const bool ok = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!ok) throw InputError(path_ + ": write failed (disk full?)");
    std::filesystem::rename(temporary_, path_);
  }

 private:
  std::string path_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
};

template <class T>
void append_little_endian(std::vector<unsigned char>& out, T value) {
  auto bits = std::bit_cast<std::array<unsigned char, sizeof(T)>>(value);
  if constexpr (std::endian::native == std::endian::big) std::reverse(bits.begin(), bits.end());
  out.insert(out.end(), bits.begin(), bits.end());
}

sim::SimulationSpec build_spec(const SimulateOptionsCli& o, std::string& unit_name) {
  sim::SimulationSpec spec;
  spec.duration_s = o.duration_s;
  spec.seed = o.seed;
  const bool output_given = o.volts_per_unit != 0.0;
  if (!o.preset.empty()) {
    const sim::Preset preset = sim::find_preset(o.preset);
    for (const CLI::Option* opt : o.noise_options) {
      if (opt->count() > 0) {
        throw InputError(opt->get_name() + " cannot be combined with --preset " + o.preset +
                         " (the preset fixes the noise model; drop one of them)");
      }
    }
    if (o.channels_option->count() > 0) {
      throw InputError("--channels cannot be combined with --preset " + o.preset + " (it has " +
                       std::to_string(preset.channels.size()) + " channels)");
    }
    if (o.units_option->count() > 0 && parse_unit(o.units).name != preset.unit) {
      throw InputError("the " + o.preset + " preset's coefficients are in " + preset.unit +
                       "; drop --units or give --units " + preset.unit);
    }
    unit_name = preset.unit;
    spec.rate_hz = o.rate_option->count() > 0 ? o.rate_hz : preset.rate_hz;
    spec.channels = preset.channels;
  } else {
    if (o.rate_option->count() == 0) {
      throw InputError("--rate HZ is required (the sample rate), unless --preset is given");
    }
    const Unit unit = parse_unit(o.units);
    if (unit.quantity != Quantity::angular_rate && unit.quantity != Quantity::acceleration &&
        unit.quantity != Quantity::dimensionless) {
      throw InputError("--units " + o.units +
                       " is not a rate unit; give the unit of the sensor output, e.g. deg/s, rad/s, m/s^2, g");
    }
    unit_name = unit.name;
    spec.rate_hz = o.rate_hz;
    if (o.channels == 0) throw InputError("--channels must be at least 1");
    for (std::size_t c = 0; c < o.channels; ++c) {
      sim::ChannelSpec ch;
      ch.noise = o.noise;
      spec.channels.push_back(ch);
    }
  }
  for (auto& ch : spec.channels) {
    // A preset keeps its own measurement range unless --range is given.
    if (o.range_option->count() > 0 || o.preset.empty()) ch.output.range_unit = o.range;
    ch.output.scale_factor = o.scale_factor * (output_given ? o.volts_per_unit : 1.0);
    ch.output.offset_output = o.offset;
    ch.output.lsb_output = o.lsb;
  }
  if (o.volts_per_unit < 0.0 || !std::isfinite(o.volts_per_unit)) {  // 0 = not given
    throw InputError("--volts-per-unit must be positive (e.g. 0.02 for the TG-100's 20 mV/(deg/s))");
  }
  return spec;
}

void run_simulate(const SimulateOptionsCli& o) {
  if (o.format != "text" && o.format != "f64" && o.format != "f32") {
    throw InputError("--format " + o.format + " is not known; use text, f64 or f32");
  }
  std::string unit;
  const sim::SimulationSpec spec = build_spec(o, unit);
  sim::Generator generator(spec);  // validates every parameter before the file is created
  const std::string output_unit =
      o.volts_per_unit != 0.0 ? "V" : (o.scale_factor != 1.0 ? unit + " (scaled)" : unit);
  const std::size_t channels = generator.channel_count();
  const unsigned threads = o.threads == 0 ? std::max(1U, std::thread::hardware_concurrency()) : o.threads;

  Sink sink(o.path, o.force);
  const bool text = o.format == "text";
  std::string header;
  header += "# imunoise simulate 0.1.0: synthetic sensor output" +
            (o.preset.empty() ? std::string() : " (preset " + o.preset + ")") + "\n";
  header += fmt::format("# rate_hz {:g}  tau0_s {:g}  samples {}  duration_s {:g}  channels {}  seed {}\n",
                        generator.rate_hz(), generator.tau0_s(), generator.sample_count(),
                        static_cast<double>(generator.sample_count()) / generator.rate_hz(), channels,
                        o.seed);
  header += fmt::format("# unit {} (noise parameters); output unit {}; format {}\n", unit, output_unit,
                        text ? "text" : o.format + " little-endian, channels interleaved");
  header += "# sample k = average rate over [k tau0, (k+1) tau0); generator xoshiro256** + ziggurat, "
            "reproducible bit for bit from the seed\n";
  const Unit parsed = parse_unit(unit);
  for (std::size_t c = 0; c < channels; ++c) {
    header += fmt::format("# {}: {}\n", generator.channel_name(c), describe(generator.channel(c), unit));
    const std::string cust = customary(generator.channel(c).model(), parsed);
    if (!cust.empty()) header += fmt::format("#   customary: {}\n", cust);
  }
  if (text) {
    for (std::size_t c = 0; c < channels; ++c) header += (c ? "\t" : "") + generator.channel_name(c);
    header += "\n";
    sink.write(header.data(), header.size());
  }

  constexpr std::size_t kFrames = 16384;
  std::vector<double> chunk(kFrames * channels);
  fmt::memory_buffer text_buffer;
  std::vector<unsigned char> bytes;
  while (const std::size_t frames = generator.generate_interleaved(chunk, threads)) {
    const std::size_t values = frames * channels;
    if (text) {
      text_buffer.clear();
      for (std::size_t k = 0; k < frames; ++k) {
        for (std::size_t c = 0; c < channels; ++c) {
          // Shortest representation that reads back to the same double.
          fmt::format_to(std::back_inserter(text_buffer), "{}", chunk[k * channels + c]);
          text_buffer.push_back(c + 1 < channels ? '\t' : '\n');
        }
      }
      sink.write(text_buffer.data(), text_buffer.size());
    } else {
      bytes.clear();
      for (std::size_t i = 0; i < values; ++i) {
        if (o.format == "f64") {
          append_little_endian(bytes, chunk[i]);
        } else {
          append_little_endian(bytes, static_cast<float>(chunk[i]));
        }
      }
      sink.write(bytes.data(), bytes.size());
    }
  }
  sink.commit();
  if (!text && !(o.path.empty() || o.path == "-")) {
    // Raw files carry no header: say what was written.
    fmt::print(stderr, "{}", header);
    fmt::print(stderr, "# wrote {} frames x {} channels ({} bytes each) to {}\n", generator.sample_count(),
               channels, o.format == "f64" ? 8 : 4, o.path);
  }
}

}  // namespace

void setup_simulate(CLI::App& app) {
  auto options = std::make_shared<SimulateOptionsCli>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "synthetic sensor output: every noise term (Q N B K R, Gauss-Markov, sinusoid, bias), "
      "saturation, scale factor / analog output, ADC; seeded, reproducible bit for bit");
  sim::NoiseModel& n = options->noise;
  options->rate_option = cmd->add_option("--rate", options->rate_hz, "sample rate (Hz)");
  cmd->add_option("--duration", options->duration_s, "record length (s)")->capture_default_str();
  auto noise = [&](const char* name, double& field, const char* help) {
    options->noise_options.push_back(cmd->add_option(name, field, help));
  };
  noise("--Q", n.q_unit_s, "angle (quantization) noise Q, unit*s (deg for deg/s): sigma = sqrt(3) Q / tau");
  noise("--N", n.n_unit_sqrt_s, "angle random walk N, unit*sqrt(s) (deg/sqrt(s)): sigma(1 s) = N");
  noise("--B", n.b_unit, "bias instability B, unit (deg/s): flicker floor 0.6643 B");
  noise("--K", n.k_unit_per_sqrt_s, "rate random walk K, unit/sqrt(s) (deg/s/sqrt(s)): sigma(3 s) = K");
  noise("--R", n.r_unit_per_s, "rate ramp R, unit/s (deg/s^2), signed");
  noise("--bias", n.bias_unit, "constant bias, unit (deg/s), signed");
  noise("--gm-sigma", n.gm_sigma_unit, "first-order Gauss-Markov standard deviation, unit");
  noise("--gm-tau", n.gm_time_s, "Gauss-Markov correlation time (s)");
  noise("--sine-amp", n.sine_amplitude_unit, "sinusoid amplitude, unit");
  noise("--sine-freq", n.sine_frequency_hz, "sinusoid frequency (Hz), at most rate/2");
  noise("--sine-phase", n.sine_phase_rad, "sinusoid phase at t = 0 (rad)");
  noise("--flicker-tau-min", n.flicker_tau_min_s,
        "lower end of the tau range where B's floor is honoured (s; default 1/rate)");
  noise("--flicker-tau-max", n.flicker_tau_max_s,
        "upper end of that range (s; default the duration); at most 12 decades wide");
  options->range_option =
      cmd->add_option("--range", options->range, "measurement range: saturate at +-range (unit)");
  cmd->add_option("--scale-factor", options->scale_factor,
                  "multiply the output by this factor (e.g. 1.001 for a +0.1% scale-factor error)");
  cmd->add_option("--volts-per-unit", options->volts_per_unit,
                  "analog output in volts: V per unit (0.02 for the TG-100's 20 mV/(deg/s))");
  cmd->add_option("--offset", options->offset, "added to the output after scaling (output unit, e.g. V)");
  cmd->add_option("--lsb", options->lsb, "ADC quantizer step in output units (0: none)");
  options->units_option = cmd->add_option("--units", options->units,
                                          "unit of the rate and of every parameter")->capture_default_str();
  cmd->add_option("--preset", options->preset,
                  "tg100: the paper's four TG-100 gyros (Table 2, 200 Hz, deg/s, range +-100 deg/s)");
  options->channels_option =
      cmd->add_option("--channels", options->channels, "independent channels with the same model")
          ->capture_default_str();
  cmd->add_option("--seed", options->seed, "random seed; the output depends only on it and the options")
      ->capture_default_str();
  cmd->add_option("--format", options->format,
                  "text (tab-separated, # header), f64 or f32 (raw little-endian, interleaved)")
      ->capture_default_str();
  cmd->add_option("-o,--output", options->path, "output FILE, or - for standard output")->required();
  cmd->add_flag("--force", options->force, "replace an existing output file");
  cmd->add_option("--threads", options->threads,
                  "generate channels in parallel (0: all cores); the output does not depend on it");
  cmd->callback([options] { run_simulate(*options); });
}

}  // namespace imunoise::cli
