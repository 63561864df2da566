#include "imunoise/redundant/unit_simulation.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <numbers>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "imunoise/error.hpp"
#include "imunoise/io/atomic_output.hpp"
#include "imunoise/sim/generator.hpp"

namespace imunoise::redundant {

std::array<double, 3> MotionProfile::mean_rate(double t0_s, double duration_s) const {
  std::array<double, 3> w = constant_rad_s;
  for (const auto& line : lines) {
    // Mean of sin over the sample: sin(mid) sin(pi f T) / (pi f T), stable for small f T.
    const double x = std::numbers::pi * line.frequency_hz * duration_s;
    const double sinc = x == 0.0 ? 1.0 : std::sin(x) / x;
    for (std::size_t a = 0; a < 3; ++a) {
      const double mid = 2 * std::numbers::pi * line.frequency_hz * (t0_s + 0.5 * duration_s) + line.phase_rad[a];
      w[a] += line.amplitude_rad_s[a] * std::sin(mid) * sinc;
    }
  }
  return w;
}

MotionProfile tumble_profile(double amplitude_rad_s) {
  MotionProfile p;
  const double f[3] = {0.5, 0.31, 0.17};
  for (std::size_t a = 0; a < 3; ++a) {
    RotationLine line;
    line.frequency_hz = f[a];
    line.amplitude_rad_s[a] = amplitude_rad_s;
    line.phase_rad[a] = static_cast<double>(a);
    p.lines.push_back(line);
  }
  return p;
}

namespace {

double number_in(std::string_view text, std::string_view term) {
  const std::string t(text);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v)) {
    throw InputError(fmt::format("--motion term '{}': '{}' is not a number", term, text));
  }
  return v;
}

constexpr const char* kMotionForms =
    "write terms joined by '+': still, tumble[:DEG_S], turn:X,Y,Z (deg/s), vibration:DEG_S:HZ";

}  // namespace

MotionProfile motion_profile(std::string_view spec) {
  constexpr double deg = std::numbers::pi / 180.0;
  MotionProfile p;
  if (spec.empty()) throw InputError(std::string("empty --motion; ") + kMotionForms);
  std::size_t start = 0;
  while (start <= spec.size()) {
    const std::size_t plus = spec.find('+', start);
    const std::string_view term = spec.substr(start, plus == std::string_view::npos ? spec.size() - start : plus - start);
    const std::size_t colon = term.find(':');
    const std::string_view name = term.substr(0, colon);
    const std::string_view args = colon == std::string_view::npos ? std::string_view{} : term.substr(colon + 1);
    if (name == "still" && args.empty()) {
      // nothing
    } else if (name == "tumble") {
      const double a = args.empty() ? 200.0 : number_in(args, term);
      const auto t = tumble_profile(a * deg);
      p.lines.insert(p.lines.end(), t.lines.begin(), t.lines.end());
    } else if (name == "turn" && !args.empty()) {
      std::size_t b = 0;
      for (std::size_t a = 0; a < 3; ++a) {
        const std::size_t comma = args.find(',', b);
        if ((a < 2) == (comma == std::string_view::npos)) {
          throw InputError(fmt::format("--motion term '{}': write turn:X,Y,Z (three rates in deg/s)", term));
        }
        p.constant_rad_s[a] += number_in(args.substr(b, a < 2 ? comma - b : std::string_view::npos), term) * deg;
        b = comma + 1;
      }
    } else if (name == "vibration" && !args.empty()) {
      const std::size_t c2 = args.find(':');
      if (c2 == std::string_view::npos) {
        throw InputError(fmt::format("--motion term '{}': write vibration:DEG_S:HZ", term));
      }
      RotationLine line;
      line.frequency_hz = number_in(args.substr(c2 + 1), term);
      const double amp = number_in(args.substr(0, c2), term) * deg;
      line.amplitude_rad_s = {amp, amp, amp};
      line.phase_rad = {0.0, 1.0, 2.0};
      p.lines.push_back(line);
    } else {
      throw InputError(fmt::format("--motion term '{}' is not known; {}", term, kMotionForms));
    }
    if (plus == std::string_view::npos) break;
    start = plus + 1;
  }
  return p;
}

sim::NoiseModel scaled_noise(sim::NoiseModel m, double to_si) {
  for (double* v : {&m.q_unit_s, &m.n_unit_sqrt_s, &m.b_unit, &m.k_unit_per_sqrt_s, &m.r_unit_per_s, &m.gm_sigma_unit,
                    &m.sine_amplitude_unit, &m.bias_unit}) {
    *v *= to_si;
  }
  return m;
}

std::vector<std::string> write_unit_records(const std::string& dir, bool force, const Geometry& geometry,
                                            std::span<const std::vector<double>> records, const std::string& unit_name,
                                            double to_si, const std::string& header) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": cannot create the directory; check the path");
  std::vector<std::string> paths;
  for (std::size_t i = 0; i < records.size(); ++i) {
    paths.push_back((fs::path(dir) / fmt::format("sensor{}.txt", i + 1)).string());
    if (!force && fs::exists(paths.back(), ec)) {
      throw InputError(paths.back() + ": file exists; imunoise does not overwrite it — choose another directory or "
                       "pass --force");
    }
  }
  std::string text;
  for (std::size_t i = 0; i < records.size(); ++i) {
    io::AtomicOutput out(paths[i], force);
    const auto& h = geometry.axes[i];
    text = header + fmt::format("# sensor {} of {} ({}), axis ({:.9g}, {:.9g}, {:.9g}), {}\n", i + 1, records.size(),
                                geometry.name, h[0], h[1], h[2], unit_name);
    for (const double v : records[i]) fmt::format_to(std::back_inserter(text), "{:.17g}\n", v / to_si);
    out.write(text.data(), text.size());
    out.commit();
  }
  return paths;
}

std::array<std::vector<double>, 3> specific_force(const MotionProfile& motion, double rate_hz, double duration_s) {
  if (!(rate_hz > 0.0) || !(duration_s > 0.0)) {
    throw InputError(fmt::format("specific_force: rate {} Hz and duration {} s must be positive", rate_hz, duration_s));
  }
  const auto len = static_cast<std::size_t>(std::llround(duration_s * rate_hz));
  const double tau0 = 1.0 / rate_hz;
  std::array<std::vector<double>, 3> f;
  for (auto& c : f) c.resize(len);
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();  // body to world
  const Eigen::Vector3d up(0.0, 0.0, motion.gravity_m_s2);
  MotionProfile vibration;
  vibration.lines = motion.vibration_m_s2;
  for (std::size_t t = 0; t < len; ++t) {
    const double t0 = static_cast<double>(t) * tau0;
    // Half a sample's rotation to mid-sample, then the other half to the next sample's start.
    const auto w = motion.mean_rate(t0, tau0);
    const Eigen::Vector3d phi = Eigen::Vector3d(w[0], w[1], w[2]) * tau0;
    const double angle = phi.norm();
    const Eigen::Matrix3d half =
        angle > 0 ? Eigen::AngleAxisd(0.5 * angle, phi / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d mid = r * half;
    const Eigen::Vector3d fb = mid.transpose() * up;
    const auto vib = vibration.mean_rate(t0 + 0.5 * tau0, 0.0);
    for (std::size_t a = 0; a < 3; ++a) f[a][t] = fb(static_cast<Eigen::Index>(a)) + vib[a];
    r = mid * half;
  }
  return f;
}

std::vector<std::vector<double>> simulate_unit(const Geometry& geometry, std::span<const UnitSensor> sensors,
                                               const MotionProfile& motion, double rate_hz, double duration_s,
                                               std::uint64_t seed) {
  const std::size_t n = geometry.size();
  if (sensors.size() != n) {
    throw InputError(fmt::format("simulate_unit: {} sensor specifications for the {} axes of geometry {}",
                                 sensors.size(), n, geometry.name));
  }
  std::vector<RotationLine> all_lines = motion.lines;
  all_lines.insert(all_lines.end(), motion.vibration_m_s2.begin(), motion.vibration_m_s2.end());
  for (const auto& line : all_lines) {
    if (!(line.frequency_hz >= 0.0) || line.frequency_hz > rate_hz / 2) {
      throw InputError(fmt::format("simulate_unit: a rotation line at {} Hz is outside 0 .. {} Hz (the Nyquist "
                                   "frequency of {} Hz)", line.frequency_hz, rate_hz / 2, rate_hz));
    }
  }
  sim::SimulationSpec spec;
  spec.rate_hz = rate_hz;
  spec.duration_s = duration_s;
  spec.seed = seed;
  bool motion_noise = false;
  for (std::size_t i = 0; i < n; ++i) {
    spec.channels.push_back({sensors[i].noise, {}, fmt::format("sensor{}", i + 1)});
    motion_noise = motion_noise || sensors[i].motion_noise_sqrt_s != 0.0;
  }
  sim::Generator gen(spec);
  const auto len = static_cast<std::size_t>(gen.sample_count());
  std::vector<std::vector<double>> out(n, std::vector<double>(len));
  {
    std::vector<std::span<double>> spans;
    for (auto& o : out) spans.emplace_back(o);
    gen.generate_planar(spans, 1);
  }
  std::vector<std::vector<double>> unit_white;
  if (motion_noise) {
    // Its own streams (another seed), so the sensors' noise is the same with or without it.
    sim::SimulationSpec white = spec;
    white.seed = seed ^ 0x5DEECE66DULL;
    for (auto& c : white.channels) {
      c.noise = sim::NoiseModel{};
      c.noise.n_unit_sqrt_s = 1.0;
    }
    sim::Generator wgen(white);
    unit_white.assign(n, std::vector<double>(len));
    std::vector<std::span<double>> spans;
    for (auto& o : unit_white) spans.emplace_back(o);
    wgen.generate_planar(spans, 1);
  }
  // Effective axes: (1 + s) (h + d_perp).
  std::vector<Axis> eff(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& h = geometry.axes[i];
    const auto& d = sensors[i].misalignment_rad;
    const double along = d[0] * h[0] + d[1] * h[1] + d[2] * h[2];
    const double s = 1.0 + 1e-6 * sensors[i].scale_factor_ppm;
    for (std::size_t a = 0; a < 3; ++a) eff[i][a] = s * (h[a] + d[a] - along * h[a]);
  }
  const double tau0 = 1.0 / rate_hz;
  bool late = false;
  bool g_sensitive = false;
  for (const auto& s : sensors) {
    late = late || s.time_offset_s != 0.0;
    g_sensitive = g_sensitive || s.g_sensitivity_rad_s_per_m_s2 != std::array<double, 3>{};
    if (!std::isfinite(s.time_offset_s) || std::abs(s.time_offset_s) > duration_s) {
      throw InputError(fmt::format("simulate_unit: time offset {} s is not finite or longer than the record",
                                   s.time_offset_s));
    }
  }
  std::array<std::vector<double>, 3> force;
  if (g_sensitive) force = specific_force(motion, rate_hz, duration_s);
  for (std::size_t t = 0; t < len; ++t) {
    const auto w_common = motion.mean_rate(static_cast<double>(t) * tau0, tau0);
    for (std::size_t i = 0; i < n; ++i) {
      const auto w = late ? motion.mean_rate(static_cast<double>(t) * tau0 + sensors[i].time_offset_s, tau0) : w_common;
      out[i][t] += eff[i][0] * w[0] + eff[i][1] * w[1] + eff[i][2] * w[2];
      if (g_sensitive && t < force[0].size()) {
        const auto& gi = sensors[i].g_sensitivity_rad_s_per_m_s2;
        out[i][t] += gi[0] * force[0][t] + gi[1] * force[1][t] + gi[2] * force[2][t];
      }
      if (motion_noise) {
        const auto& h = geometry.axes[i];
        const double sensed = std::abs(h[0] * w[0] + h[1] * w[1] + h[2] * w[2]);
        out[i][t] += sensors[i].motion_noise_sqrt_s * sensed * unit_white[i][t];
      }
    }
  }
  return out;
}

}  // namespace imunoise::redundant
