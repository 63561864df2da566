// imunoise simulate: synthetic sensor output with a given noise model (or the paper's preset),
// streamed in chunks to text or raw binary, reproducible bit for bit from its seed.
#include <algorithm>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <fmt/format.h>

#include "commands.hpp"
#include "imunoise/error.hpp"
#include "imunoise/io/atomic_output.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/redundant/unit_simulation.hpp"
#include "imunoise/units.hpp"
#include "imunoise/sim/describe.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/sim/request.hpp"

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
  std::string unit_geometry;           // --unit G: a redundant unit, one file per sensor into -o DIR
  std::string motion = "tumble";       // --motion SPEC (redundant::motion_profile)
  std::vector<double> sensor_scale_ppm;  // --sensor-scale-ppm: one per sensor
  // Options given on the command line (to detect conflicts with --preset).
  std::vector<CLI::Option*> noise_options;
  CLI::Option* rate_option = nullptr;
  CLI::Option* channels_option = nullptr;
  CLI::Option* units_option = nullptr;
  CLI::Option* range_option = nullptr;
};

sim::SimulationRequest to_request(const SimulateOptionsCli& o) {
  sim::SimulationRequest r;
  if (o.rate_option->count() > 0) r.rate_hz = o.rate_hz;
  r.duration_s = o.duration_s;
  r.seed = o.seed;
  r.noise = o.noise;
  for (const CLI::Option* opt : o.noise_options) {
    if (opt->count() > 0) r.noise_given.push_back(opt->get_name());
  }
  if (o.range_option->count() > 0) r.range_unit = o.range;
  r.scale_factor = o.scale_factor;
  r.volts_per_unit = o.volts_per_unit;
  r.offset_output = o.offset;
  r.lsb_output = o.lsb;
  if (o.units_option->count() > 0) r.unit = o.units;
  r.preset = o.preset;
  if (o.channels_option->count() > 0) r.channels = o.channels;
  return r;
}

// --unit: a redundant unit under motion, each sensor its own stream of the same noise model
// (redundant/unit_simulation.hpp does the work); one text file per sensor, read back by
// `imunoise redundant --in-motion DIR/sensor*.txt --rate R --units U`.
void run_simulate_unit(const SimulateOptionsCli& o) {
  if (!o.preset.empty() || o.format != "text" || o.channels_option->count() > 0) {
    throw InputError("--unit writes text files, one per sensor: drop --preset, --format and --channels");
  }
  if (o.rate_option->count() == 0) throw InputError("--unit needs --rate HZ");
  if (o.range_option->count() > 0 || o.scale_factor != 1.0 || o.volts_per_unit != 0.0 || o.offset != 0.0 ||
      o.lsb != 0.0) {
    throw InputError("--unit simulates rates (with --sensor-scale-ppm per sensor): drop --range, --scale-factor, "
                     "--volts-per-unit, --offset and --lsb");
  }
  const auto geometry = redundant::make_geometry(o.unit_geometry);
  if (!o.sensor_scale_ppm.empty() && o.sensor_scale_ppm.size() != geometry.size()) {
    throw InputError(fmt::format("--sensor-scale-ppm: {} values for the {} sensors of {}", o.sensor_scale_ppm.size(),
                                 geometry.size(), geometry.name));
  }
  const Unit unit = parse_unit(o.units);
  std::vector<redundant::UnitSensor> sensors(geometry.size());
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    sensors[i].noise = redundant::scaled_noise(o.noise, unit.to_si);
    if (!o.sensor_scale_ppm.empty()) sensors[i].scale_factor_ppm = o.sensor_scale_ppm[i];
  }
  const auto records = redundant::simulate_unit(geometry, sensors, redundant::motion_profile(o.motion), o.rate_hz,
                                                o.duration_s, o.seed);
  const std::string header = fmt::format("# imunoise simulate --unit {} --motion {} --rate {} --duration {} --seed {}\n",
                                         geometry.name, o.motion, o.rate_hz, o.duration_s, o.seed);
  const auto paths = redundant::write_unit_records(o.path, o.force, geometry, records, unit.name, unit.to_si, header);
  fmt::print(stderr, "# wrote {} sensors x {} samples ({}) to {}/sensor1.txt .. sensor{}.txt\n", paths.size(),
             records.empty() ? 0 : records[0].size(), unit.name, o.path, paths.size());
}

void run_simulate(const SimulateOptionsCli& o) {
  if (!o.unit_geometry.empty()) {
    run_simulate_unit(o);
    return;
  }
  if (o.format != "text" && o.format != "f64" && o.format != "f32") {
    throw InputError("--format " + o.format + " is not known; use text, f64 or f32");
  }
  const sim::SimulationPlan plan = sim::plan_simulation(to_request(o));
  const std::string& unit = plan.unit;
  const std::string& output_unit = plan.output_unit;
  sim::Generator generator(plan.spec);  // validates every parameter before the file is created
  const std::size_t channels = generator.channel_count();
  const unsigned threads = o.threads == 0 ? std::max(1U, std::thread::hardware_concurrency()) : o.threads;

  io::AtomicOutput sink(o.path, o.force);
  const bool text = o.format == "text";
  const std::string format = text ? "text" : o.format + " little-endian, channels interleaved";
  std::string header = sim::simulation_header(generator, o.preset, o.seed, unit, output_unit, format);
  if (text) {
    for (std::size_t c = 0; c < channels; ++c) header += (c ? "\t" : "") + generator.channel_name(c);
    header += "\n";
    sink.write(header.data(), header.size());
  }

  sim::write_samples(generator, text ? sim::SampleFormat::text
                                      : o.format == "f64" ? sim::SampleFormat::f64 : sim::SampleFormat::f32,
                     threads, [&sink](const void* data, std::size_t bytes) { sink.write(data, bytes); });
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
  cmd->add_option("-o,--output", options->path, "output FILE, or - for standard output (with --unit: a directory)")
      ->required();
  cmd->add_option("--unit", options->unit_geometry,
                  "a redundant unit of this geometry (tetra, dodeca, triads:K, cone:N:DEG, FILE) under --motion: "
                  "one text file per sensor in -o DIR, each sensor its own noise stream");
  cmd->add_option("--motion", options->motion,
                  "with --unit: still, tumble[:DEG_S], turn:X,Y,Z, vibration:DEG_S:HZ, joined by '+'")
      ->capture_default_str();
  cmd->add_option("--sensor-scale-ppm", options->sensor_scale_ppm,
                  "with --unit: each sensor's scale-factor error (ppm), one per sensor")
      ->delimiter(',');
  cmd->add_flag("--force", options->force, "replace an existing output file");
  cmd->add_option("--threads", options->threads,
                  "generate channels in parallel (0: all cores); the output does not depend on it");
  cmd->callback([options] { run_simulate(*options); });
}

}  // namespace imunoise::cli
