#include "imunoise/study/in_motion_container.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "imunoise/error.hpp"
#include "imunoise/io/recording.hpp"
#include "imunoise/io/timestamps.hpp"
#include "imunoise/units.hpp"

namespace imunoise::study {
namespace {

// One x/y/z triple of channels of one topic, on its own times (absolute: seconds since the
// first topic's origin).
struct Instance {
  std::string topic;
  std::string prefix;                       // "gyro0", "gyro", "accel1"
  std::array<const io::Channel*, 3> axes{};
  std::vector<double> time_s;
  std::string label() const { return fmt::format("topic {} instance {}", topic, prefix); }
};

std::optional<std::int64_t> origin_ns(const io::Recording& r) {
  const std::string& o = r.time_origin;
  if (o.size() < 4 || o.substr(o.size() - 3) != " ns") return std::nullopt;
  std::int64_t v = 0;
  const auto [p, ec] = std::from_chars(o.data(), o.data() + o.size() - 3, v);
  if (ec != std::errc() || p != o.data() + o.size() - 3) return std::nullopt;
  return v;
}

// The instances of `kind` ("gyro" or "accel") in a recording, in channel order.
std::vector<Instance> instances_of(const io::Recording& r, const std::string& kind, double shift_s) {
  std::vector<Instance> out;
  std::map<std::string, std::size_t> index;
  for (const auto& c : r.channels) {
    if (c.name.rfind(kind, 0) != 0 || c.name.size() < kind.size() + 2) continue;
    const std::string prefix = c.name.substr(0, c.name.size() - 2);
    const char axis = c.name.back();
    if (c.name[c.name.size() - 2] != '_' || (axis != 'x' && axis != 'y' && axis != 'z')) continue;
    auto [it, added] = index.try_emplace(prefix, out.size());
    if (added) out.push_back(Instance{r.stream, prefix, {}, {}});
    out[it->second].axes[static_cast<std::size_t>(axis - 'x')] = &c;
  }
  for (auto& inst : out) {
    for (std::size_t a = 0; a < 3; ++a) {
      if (inst.axes[a] == nullptr) {
        throw InputError(fmt::format("{}: {} has no channel {}_{}: an instance needs its three axes; channels: {}",
                                     r.source, inst.label(), inst.prefix, "xyz"[a], r.channel_list()));
      }
    }
    const auto& t = r.times(*inst.axes[0]);
    for (std::size_t a = 1; a < 3; ++a) {
      if (r.times(*inst.axes[a]) != t) {
        throw InputError(fmt::format("{}: the axes of {} have different timestamps", r.source, inst.label()));
      }
    }
    if (t.empty()) throw InputError(fmt::format("{}: {} has no timestamps", r.source, inst.label()));
    inst.time_s.resize(t.size());
    for (std::size_t q = 0; q < t.size(); ++q) inst.time_s[q] = t[q] + shift_s;
  }
  return out;
}

std::size_t nearest(std::span<const double> t, double x) {
  const auto it = std::lower_bound(t.begin(), t.end(), x);
  if (it == t.begin()) return 0;
  if (it == t.end()) return t.size() - 1;
  const auto j = static_cast<std::size_t>(it - t.begin());
  return x - t[j - 1] <= t[j] - x ? j - 1 : j;
}

Unit unit_of(const io::Channel& c, const std::string& given, const std::string& source) {
  if (c.unit) {
    if (!given.empty() && parse_unit(given).name != c.unit->name) {
      throw InputError(fmt::format("{}: channel {} is in {} according to the file, but --units says {}; drop --units",
                                   source, c.name, c.unit->name, given));
    }
    return *c.unit;
  }
  if (given.empty()) {
    throw InputError(fmt::format("{}: channel {} states no unit; give --units", source, c.name));
  }
  return parse_unit(given);
}

std::vector<std::string> milliseconds(std::span<const double> s) {
  std::vector<std::string> out;
  for (const double x : s) out.push_back(fmt::format("{:.4g}", 1e3 * x));
  return out;
}

}  // namespace

bool is_container_file(const std::string& path) {
  if (path == "-" || !std::filesystem::exists(path)) return false;
  return io::detect_container(path).has_value();
}

InstancePairing pair_instances(std::span<const std::span<const double>> times_s, std::span<const std::string> names) {
  InstancePairing out;
  const std::size_t n = times_s.size();
  if (n == 0) return out;
  std::vector<double> dt(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Gaps and disorder refused, naming the instance (io::check_timing's message and fix).
    dt[i] = io::check_timing(times_s[i], names[i]).median_dt_s;
  }
  for (std::size_t i = 1; i < n; ++i) {
    if (std::abs(dt[i] / dt[0] - 1.0) > 1e-3) {
      throw InputError(fmt::format(
          "{} is sampled at {:.9g} Hz but {} at {:.9g} Hz (1 / median interval): the in-motion analysis pairs the "
          "instances sample by sample and never resamples a gyro (it would filter the noise being measured); "
          "fix: log the IMUs at one rate", names[i], 1.0 / dt[i], names[0], 1.0 / dt[0]));
    }
  }
  double start = times_s[0].front();
  for (std::size_t i = 1; i < n; ++i) start = std::max(start, times_s[i].front());
  const auto& t0 = times_s[0];
  const auto r0 = static_cast<std::size_t>(
      std::lower_bound(t0.begin(), t0.end(), start - 0.5 * dt[0]) - t0.begin());
  if (r0 >= t0.size()) {
    throw InputError(fmt::format("{} ends before {} begins: the instances do not overlap", names[0], names[n - 1]));
  }
  out.first.assign(n, 0);
  out.first[0] = r0;
  out.count = t0.size() - r0;
  for (std::size_t i = 1; i < n; ++i) {
    out.first[i] = nearest(times_s[i], t0[r0]);
    out.count = std::min(out.count, times_s[i].size() - out.first[i]);
  }
  if (out.count < 8) {
    throw InputError(fmt::format("the instances {} ... {} overlap by {} samples only; the analysis needs at least 8",
                                 names[0], names[n - 1], out.count));
  }
  out.mean_offset_s.assign(n, 0.0);
  out.spread_s.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const auto& ti = times_s[i];
    const double first = ti[out.first[i]] - t0[r0];
    double lo = first;
    double hi = first;
    long double sum = 0.0L;
    for (std::size_t q = 0; q < out.count; ++q) {
      const double o = ti[out.first[i] + q] - t0[r0 + q];
      if (std::abs(o - first) > 0.5 * dt[0]) {
        throw InputError(fmt::format(
            "{} slips against {}: at pair {} (t = {:.6f} s) their sample times differ by {:.4g} ms, at the first "
            "pair by {:.4g} ms, a change of more than half a sample ({:.4g} ms): the clocks drift (rates {:.9g} and "
            "{:.9g} Hz); the in-motion analysis pairs samples and never resamples a gyro; fix: cut the log to a span "
            "without the slip (--skip, or a shorter log)",
            names[i], names[0], q, t0[r0 + q], 1e3 * o, 1e3 * first, 0.5e3 * dt[0], 1.0 / dt[i], 1.0 / dt[0]));
      }
      lo = std::min(lo, o);
      hi = std::max(hi, o);
      sum += o;
    }
    out.mean_offset_s[i] = static_cast<double>(sum / static_cast<long double>(out.count));
    out.spread_s[i] = hi - lo;
  }
  return out;
}

std::array<std::vector<double>, 3> mean_specific_force(std::span<const Record> accels, std::size_t samples) {
  std::array<std::vector<double>, 3> f;
  if (accels.empty()) return f;
  if (accels.size() % 3 != 0) {
    throw InputError(fmt::format("--accel: {} recordings; give the accelerometers as co-aligned triads in body axes, "
                                 "x y z of each (a multiple of 3)", accels.size()));
  }
  for (auto& c : f) c.assign(samples, 0.0);
  const double triads = static_cast<double>(accels.size() / 3);
  for (std::size_t i = 0; i < accels.size(); ++i) {
    const auto& r = accels[i];
    if (r.rate_si.size() != samples) {
      throw InputError(fmt::format("--accel: {} has {} samples but the gyros {}: the accelerometers must be "
                                   "synchronous with the gyros", r.source, r.rate_si.size(), samples));
    }
    for (std::size_t t = 0; t < samples; ++t) f[i % 3][t] += r.rate_si[t] / triads;
  }
  return f;
}

ContainerUnit read_container_unit(const load::LoadOptions& options, std::span<const std::string> topics,
                                  std::span<const std::string> accel_topics) {
  if (!options.column.empty() || !options.time_column.empty() || !options.binary.empty()) {
    throw InputError(options.file + ": --column, --time-column and --binary do not apply to a container holding the "
                     "whole unit: every gyro instance of --topic is read, with the file's timestamps");
  }
  if (topics.empty()) {
    throw InputError(options.file + ": a container holding the whole unit needs --topic (e.g. sensor_gyro for a "
                     "PX4 log, or /imu0,/imu1,/imu2 for a bag)");
  }
  std::vector<io::Recording> recordings;
  std::vector<bool> gyro_topic;
  for (const auto& t : topics) {
    recordings.push_back(io::read_recording(options.file, io::RecordingOptions{t, options.dataset, options.time_dataset}));
    gyro_topic.push_back(true);
  }
  for (const auto& t : accel_topics) {
    recordings.push_back(io::read_recording(options.file, io::RecordingOptions{t, options.dataset, options.time_dataset}));
    gyro_topic.push_back(false);
  }
  const auto origin0 = origin_ns(recordings.front());
  std::vector<Instance> gyros;
  std::vector<Instance> accels;
  for (std::size_t k = 0; k < recordings.size(); ++k) {
    double shift = 0.0;
    if (k > 0) {
      const auto o = origin_ns(recordings[k]);
      if (!o || !origin0) {
        throw InputError(fmt::format("{}: the topics' time origins cannot be related ({}, {})", options.file,
                                     recordings.front().time_origin, recordings[k].time_origin));
      }
      shift = static_cast<double>(*o - *origin0) * 1e-9;
    }
    if (gyro_topic[k]) {
      auto g = instances_of(recordings[k], "gyro", shift);
      if (g.empty()) {
        throw InputError(fmt::format("{}: topic {} has no gyro channels (gyro_x.. or gyroK_x..); channels: {}",
                                     options.file, recordings[k].stream, recordings[k].channel_list()));
      }
      std::move(g.begin(), g.end(), std::back_inserter(gyros));
    }
    auto a = instances_of(recordings[k], "accel", shift);
    if (!gyro_topic[k] && a.empty()) {
      throw InputError(fmt::format("{}: topic {} has no accelerometer channels (accel_x.. or accelK_x..); channels: {}",
                                   options.file, recordings[k].stream, recordings[k].channel_list()));
    }
    std::move(a.begin(), a.end(), std::back_inserter(accels));
  }
  std::vector<std::span<const double>> times;
  std::vector<std::string> names;
  for (const auto& g : gyros) {
    times.emplace_back(g.time_s);
    names.push_back(options.file + " " + g.label());
  }
  const InstancePairing pairing = pair_instances(times, names);
  ContainerUnit unit;
  unit.instance_offset_s = pairing.mean_offset_s;
  unit.instance_offset_spread_s = pairing.spread_s;
  const double rate_hz = 1.0 / io::analyze_timing(times[0], names[0]).median_dt_s;
  if (options.rate_hz > 0 && std::abs(rate_hz / options.rate_hz - 1.0) > 0.01) {
    throw InputError(fmt::format("{}: --rate {} Hz disagrees with the file's timestamps ({:.6g} Hz from the median "
                                 "interval); drop --rate", options.file, options.rate_hz, rate_hz));
  }
  const preprocess::PipelineOptions pipeline = load::pipeline_options(options);
  for (std::size_t i = 0; i < gyros.size(); ++i) {
    const auto& g = gyros[i];
    for (std::size_t a = 0; a < 3; ++a) {
      const io::Channel& c = *g.axes[a];
      Record r;
      r.name = c.name;
      r.source = fmt::format("{} [{} {}]", options.file, g.topic, c.name);
      r.kind = InputKind::rate;
      r.rate_hz = rate_hz;
      r.rate_unit = unit_of(c, options.units, options.file);
      r.unit_given = true;
      r.format = std::string(io::format_name(recordings.front().format));
      r.stream = g.topic;
      r.channel = c.name;
      std::vector<double> values(c.values.begin() + static_cast<std::ptrdiff_t>(pairing.first[i]),
                                 c.values.begin() + static_cast<std::ptrdiff_t>(pairing.first[i] + pairing.count));
      for (std::size_t q = 0; q < values.size(); ++q) {
        if (!std::isfinite(values[q])) {
          throw InputError(fmt::format("{}: {} sample {} is not finite (NaN or Inf); the analysis needs every sample",
                                       options.file, c.name, pairing.first[i] + q));
        }
        values[q] *= r.rate_unit.to_si;
      }
      r.timing = io::analyze_timing(std::span(g.time_s).subspan(pairing.first[i], pairing.count), r.source);
      if (i > 0) {
        r.notes.push_back(fmt::format("paired with {} sample by sample: offset {:.4g} ms (mean), spread {:.4g} ms",
                                      gyros[0].label(), 1e3 * pairing.mean_offset_s[i], 1e3 * pairing.spread_s[i]));
      }
      unit.gyros.push_back(load::finish_rates(std::move(r), std::move(values), pipeline, {}, {}, true));
    }
  }
  unit.notes.push_back(fmt::format(
      "{} gyro instances of {} paired sample by sample on {}'s times ({} pairs at {:.6g} Hz; no resampling); mean "
      "offsets {} ms, spreads {} ms",
      gyros.size(), options.file, gyros[0].label(), pairing.count, rate_hz,
      fmt::join(milliseconds(pairing.mean_offset_s), ", "), fmt::join(milliseconds(pairing.spread_s), ", ")));
  // The accelerometers, interpolated onto the gyros' (paired) times and averaged.
  if (!accels.empty()) {
    const std::span<const double> tg = std::span(gyros[0].time_s).subspan(pairing.first[0], pairing.count);
    for (auto& f : unit.specific_force_m_s2) f.assign(pairing.count, 0.0);
    for (const auto& inst : accels) {
      const auto& ta = inst.time_s;
      const std::string where = options.file + " " + inst.label();
      const double dta = io::analyze_timing(ta, where).median_dt_s;
      std::array<double, 3> to_si{};
      for (std::size_t a = 0; a < 3; ++a) to_si[a] = unit_of(*inst.axes[a], "", options.file).to_si;
      std::size_t j = 0;
      for (std::size_t q = 0; q < tg.size(); ++q) {
        const double t = tg[q];
        while (j + 1 < ta.size() && ta[j + 1] < t) ++j;
        // Within one interval outside the accelerometer's span (its instants are not the gyros'):
        // its first or last sample.
        const bool before = t < ta.front() && ta.front() - t <= dta;
        const bool after = t > ta.back() && t - ta.back() <= dta;
        if (before || after) {
          const std::size_t e = before ? 0 : ta.size() - 1;
          for (std::size_t a = 0; a < 3; ++a) {
            unit.specific_force_m_s2[a][q] += inst.axes[a]->values[e] * to_si[a] / static_cast<double>(accels.size());
          }
          continue;
        }
        if (t < ta.front() || t > ta.back() || j + 1 >= ta.size() || ta[j + 1] - ta[j] > 2.0 * dta) {
          throw InputError(fmt::format(
              "{}: no accelerometer samples around the gyro time {:.6f} s (its samples span {:.6f} .. {:.6f} s, a "
              "gap of more than two intervals there or the gyros outside it); fix: cut the log to a span both cover",
              where, t, ta.front(), ta.back()));
        }
        const double u = (t - ta[j]) / (ta[j + 1] - ta[j]);
        for (std::size_t a = 0; a < 3; ++a) {
          const auto& v = inst.axes[a]->values;
          unit.specific_force_m_s2[a][q] +=
              ((1.0 - u) * v[j] + u * v[j + 1]) * to_si[a] / static_cast<double>(accels.size());
        }
      }
    }
    unit.accel_instances = accels.size();
    unit.notes.push_back(fmt::format("specific force: the mean of {} accelerometer instance(s), linearly interpolated "
                                     "onto the gyros' times (a regressor of the g-sensitivity, not analysed)",
                                     accels.size()));
  }
  return unit;
}

}  // namespace imunoise::study
