#include "imunoise/load/read_channels.hpp"

#include <cmath>
#include <filesystem>
#include <variant>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/io/binary_reader.hpp"
#include "imunoise/io/text_reader.hpp"

namespace imunoise::load {
namespace {

io::Recording read_container(const ChannelsOptions& options) {
  if (!options.binary.empty()) throw InputError(options.file + ": a binary layout is for raw sample files; drop it");
  if (!options.time_column.empty()) {
    throw InputError(options.file + ": a time column is for text files; this file's timestamps are read from "
                     "the container (HDF5: the time dataset)");
  }
  io::RecordingOptions read;
  read.topic = options.topic;
  read.dataset = options.dataset;
  read.time_dataset = options.time_dataset;
  // One time axis for the channels kept (a PX4 log's sensor instances each have their own).
  return io::select_channels(io::read_recording(options.file, read), options.columns);
}

io::Recording read_binary(const ChannelsOptions& options) {
  if (!options.time_column.empty()) {
    throw InputError(options.file + ": raw binary files hold no timestamps; give the rate instead");
  }
  io::BinaryReadOptions read;
  read.format = options.binary.empty() ? *io::binary_format_from_extension(options.file)
                                       : io::parse_binary_format(options.binary);
  read.channels = options.channels;
  std::vector<std::size_t> selected;
  for (const auto& name : options.columns) {
    const auto selector = io::parse_column_selector(name);
    if (!std::holds_alternative<std::size_t>(selector)) {
      throw InputError(options.file + ": raw binary channels are chosen by 0-based index, got '" + name + "'");
    }
    selected.push_back(std::get<std::size_t>(selector));
  }
  if (selected.empty()) {
    for (std::size_t c = 0; c < options.channels; ++c) selected.push_back(c);
  }
  io::Recording recording;
  recording.source = options.file;
  recording.format = io::RecordingFormat::binary;
  for (const std::size_t c : selected) {
    read.column = c;
    recording.channels.push_back({"channel " + std::to_string(c), std::nullopt, io::read_binary_file(options.file, read)});
  }
  return recording;
}

}  // namespace

FileRecording read_channels(const ChannelsOptions& options) {
  if (!std::filesystem::exists(options.file)) throw InputError(options.file + ": no such file; check the path");
  if (options.rate_hz && (!(*options.rate_hz > 0.0) || !std::isfinite(*options.rate_hz))) {
    throw InputError(fmt::format("{}: the rate must be positive and finite (Hz), got {:g}", options.file, *options.rate_hz));
  }
  const bool binary = !options.binary.empty() || io::binary_format_from_extension(options.file).has_value();
  const bool container = !options.topic.empty() || !options.dataset.empty() || !options.time_dataset.empty() ||
                         (!binary && io::detect_container(options.file).has_value());
  FileRecording out;
  if (container) {
    out.recording = read_container(options);
  } else if (binary) {
    out.recording = read_binary(options);
  } else {
    out.recording = io::read_text_recording(options.file, options.columns, options.time_column);
  }
  if (!out.recording.time_s.empty()) {
    out.timing = io::analyze_timing(out.recording.time_s, out.recording.source);
    io::require_ordered(*out.timing, out.recording.source);
    out.rate_hz = out.timing->rate_hz;
    if (options.rate_hz && std::abs(out.rate_hz / *options.rate_hz - 1.0) > 0.01) {
      throw InputError(fmt::format("{}: rate {:g} Hz disagrees with the file's timestamps ({:.6g} Hz from the "
                                   "median interval); drop the rate",
                                   options.file, *options.rate_hz, out.rate_hz));
    }
  } else if (options.rate_hz) {
    out.rate_hz = *options.rate_hz;
  }
  return out;
}

}  // namespace imunoise::load
