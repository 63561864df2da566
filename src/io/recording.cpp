#include "imunoise/io/recording.hpp"

#include <algorithm>
#include <array>
#include <fstream>

#include "byte_cursor.hpp"
#include "imunoise/error.hpp"
#include "imunoise/io/imu_containers.hpp"
#include "imunoise/io/text_reader.hpp"
#include "imunoise/io/timestamps.hpp"

namespace imunoise::io {

std::string_view format_name(RecordingFormat format) {
  switch (format) {
    case RecordingFormat::text: return "text";
    case RecordingFormat::binary: return "binary";
    case RecordingFormat::euroc: return "EuRoC CSV";
    case RecordingFormat::hdf5: return "HDF5";
    case RecordingFormat::ros1_bag: return "ROS 1 bag";
    case RecordingFormat::mcap: return "MCAP";
    case RecordingFormat::ros2_db3: return "ROS 2 bag (SQLite)";
    case RecordingFormat::ulog: return "PX4 ULog";
  }
  return "unknown";
}

std::string Recording::channel_list() const {
  std::string out;
  for (const auto& c : channels) {
    if (!out.empty()) out += ", ";
    out += c.name;
  }
  return out;
}

const Channel& Recording::channel(std::string_view name) const {
  for (const auto& c : channels) {
    if (c.name == name) return c;
  }
  if (!name.empty() && std::all_of(name.begin(), name.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) {
    std::size_t index = 0;
    for (char ch : name) index = std::min<std::size_t>(index * 10 + static_cast<std::size_t>(ch - '0'), 1u << 30);
    if (index < channels.size()) return channels[index];
  }
  throw InputError(source + ": no channel '" + std::string(name) + "'; it has " +
                   std::to_string(channels.size()) + " channel" + (channels.size() == 1 ? "" : "s") +
                   ": " + channel_list() + "; fix: pass --column NAME or a 0-based index");
}

std::optional<RecordingFormat> detect_container(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    if (std::filesystem::exists(path / "metadata.yaml", ec)) return RecordingFormat::ros2_db3;
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open; fix: check the path and permissions");
  std::array<char, 64> head{};
  in.read(head.data(), head.size());
  const std::string_view h(head.data(), static_cast<std::size_t>(in.gcount()));
  if (h.starts_with("#ROSBAG V")) return RecordingFormat::ros1_bag;
  if (h.starts_with("\x89MCAP")) return RecordingFormat::mcap;
  if (h.starts_with("\x89HDF\r\n\x1a\n")) return RecordingFormat::hdf5;
  if (h.starts_with(std::string_view("SQLite format 3\0", 16))) return RecordingFormat::ros2_db3;
  if (h.starts_with("ULog\x01\x12\x35")) return RecordingFormat::ulog;
  // By extension: the reader then says why the content is not what the name claims.
  const auto ext = path.extension();
  if (ext == ".ulg") return RecordingFormat::ulog;
  if (ext == ".db3") return RecordingFormat::ros2_db3;
  // EuRoC/ASL: "#timestamp [ns],w_RS_S_x [rad s^-1],..." (optionally after a UTF-8 BOM).
  std::string_view line = h;
  if (line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
  if (line.starts_with("#timestamp") && line.find("w_RS_S_x") != std::string_view::npos) {
    return RecordingFormat::euroc;
  }
  return std::nullopt;
}

Recording read_recording(const std::filesystem::path& path, const RecordingOptions& options) {
  const auto format = detect_container(path);
  const std::string source = path.string();
  auto refuse = [&](std::string_view option, std::string_view needs) {
    throw InputError(source + ": " + std::string(option) + " applies to " + std::string(needs) +
                     " files, but this is a " + std::string(format_name(*format)) + " file; fix: drop " +
                     std::string(option));
  };
  if (!format) {
    throw InputError(source + ": not a ROS 1 bag, ROS 2 bag, MCAP, PX4 ULog, HDF5 or EuRoC IMU file (no known "
                     "magic number or header); fix: for text or raw binary samples drop --topic/--dataset");
  }
  switch (*format) {
    case RecordingFormat::ros1_bag:
    case RecordingFormat::mcap:
      if (!options.dataset.empty()) refuse("--dataset", "HDF5");
      if (!options.time_dataset.empty()) refuse("--time-dataset", "HDF5");
      return *format == RecordingFormat::mcap ? read_mcap(path, options.topic)
                                              : read_ros1_bag(path, options.topic);
    case RecordingFormat::ros2_db3:
    case RecordingFormat::ulog:
      if (!options.dataset.empty()) refuse("--dataset", "HDF5");
      if (!options.time_dataset.empty()) refuse("--time-dataset", "HDF5");
      return *format == RecordingFormat::ulog ? read_ulog(path, options.topic) : read_ros2_db3(path, options.topic);
    case RecordingFormat::hdf5:
      if (!options.topic.empty()) refuse("--topic", "ROS bag, MCAP and ULog");
      return read_hdf5(path, options.dataset, options.time_dataset);
    case RecordingFormat::euroc:
      if (!options.topic.empty()) refuse("--topic", "ROS bag, MCAP and ULog");
      if (!options.dataset.empty()) refuse("--dataset", "HDF5");
      return read_euroc(path);
    default:
      break;
  }
  throw InputError(source + ": unsupported container; fix: convert it to text");
}

std::string describe_streams(const std::vector<StreamInfo>& streams, std::string_view noun) {
  if (streams.empty()) return "  (no " + std::string(noun) + "s)\n";
  std::size_t width = 0;
  for (const auto& s : streams) width = std::max(width, s.name.size());
  std::string out;
  for (const auto& s : streams) {
    out += "  " + s.name + std::string(width - s.name.size(), ' ') + "  " + s.type + "  " +
           std::to_string(s.count) + (noun == "dataset" ? " rows\n" : " messages\n");
  }
  return out;
}

Recording select_channels(Recording recording, const std::vector<std::string>& names) {
  std::vector<Channel> kept;
  for (const auto& name : names) kept.push_back(recording.channel(name));
  if (names.empty()) kept = std::move(recording.channels);
  if (std::any_of(kept.begin(), kept.end(), [](const auto& c) { return !c.time_s.empty(); })) {
    std::vector<double> time = recording.times(kept.front());
    for (const auto& c : kept) {
      if (recording.times(c) != time) {
        throw InputError(recording.source + ": channels " + kept.front().name + " and " + c.name +
                         " were sampled at different times (separate sensors); fix: choose the channels of one "
                         "sensor (e.g. " + kept.front().name + " with its y and z)");
      }
    }
    recording.time_s = std::move(time);
    for (auto& c : kept) c.time_s.clear();
  }
  recording.channels = std::move(kept);
  return recording;
}

Recording read_text_recording(const std::filesystem::path& path, std::vector<std::string> columns,
                              const std::string& time_column) {
  Recording r;
  r.source = path.string();
  r.format = RecordingFormat::text;
  TextReadOptions options;
  if (!time_column.empty()) options.time_column = parse_column_selector(time_column);
  if (columns.empty()) {
    // Learn the layout from the first column, then read every column.
    TextReadOptions first;
    first.column = std::size_t{0};
    const TextColumns probe = read_text_file(path, first);
    std::optional<std::size_t> time_index;
    if (options.time_column) {
      if (const auto* index = std::get_if<std::size_t>(&*options.time_column)) {
        time_index = *index;
      } else {
        const auto& name = std::get<std::string>(*options.time_column);
        const auto it = std::find(probe.header.begin(), probe.header.end(), name);
        if (it != probe.header.end()) time_index = static_cast<std::size_t>(it - probe.header.begin());
      }
    }
    for (std::size_t k = 0; k < probe.column_count; ++k) {
      if (k != time_index) columns.push_back(std::to_string(k));
    }
  }
  for (const auto& name : columns) {
    options.column = parse_column_selector(name);
    TextColumns text = read_text_file(path, options);
    if (r.channels.empty() && options.time_column) {
      r.time_s = std::move(text.time_s);
      r.time_origin = text.time_origin + " " + text.time_unit.name;
    }
    const std::string channel_name =
        text.header.empty() ? "column " + std::to_string(text.value_column) : text.header[text.value_column];
    r.channels.push_back(Channel{channel_name, std::nullopt, std::move(text.values)});
  }
  if (r.channels.empty()) throw InputError(r.source + ": no value columns besides the time column; fix: add one");
  return r;
}

namespace detail {

Recording imu_recording(ImuColumns&& columns, std::string source, RecordingFormat format,
                        std::string topic, std::string type) {
  if (columns.stamp_ns.empty()) {
    throw InputError(source + ": topic " + topic + " has no messages; fix: choose a topic that has some");
  }
  Recording r;
  r.source = std::move(source);
  r.format = format;
  r.stream = std::move(topic);
  r.message_type = std::move(type);
  r.time_s = relative_seconds_from_ns(columns.stamp_ns);
  r.time_origin = std::to_string(columns.stamp_ns.front()) + " ns";
  static constexpr std::array<const char*, 6> names = {"gyro_x",  "gyro_y",  "gyro_z",
                                                       "accel_x", "accel_y", "accel_z"};
  for (std::size_t i = 0; i < 6; ++i) {
    r.channels.push_back(Channel{names[i], parse_unit(i < 3 ? "rad/s" : "m/s^2"), std::move(columns.v[i])});
  }
  return r;
}

}  // namespace detail
}  // namespace imunoise::io
