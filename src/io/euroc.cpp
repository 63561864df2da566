// EuRoC / ASL IMU CSV: "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],
// w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]". The header is a
// '#' comment to the text reader, so it is parsed here; the columns are read through the text
// reader's public API (one value column per pass, with column 0 as integer-ns time).
#include <fstream>

#include "imunoise/error.hpp"
#include "imunoise/io/imu_containers.hpp"
#include "imunoise/io/text_reader.hpp"

namespace imunoise::io {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// "rad s^-1" -> rad/s, "m s^-2" -> m/s^2, "ns" -> ns: the EuRoC spelling of units.
Unit euroc_unit(std::string_view text, const std::string& source) {
  std::string t(trim(text));
  if (t.ends_with(" s^-1")) t = t.substr(0, t.size() - 5) + "/s";
  else if (t.ends_with(" s^-2")) t = t.substr(0, t.size() - 5) + "/s^2";
  try {
    return parse_unit(t);
  } catch (const InputError&) {
    throw InputError(source + ":1: unknown unit '[" + std::string(trim(text)) +
                     "]' in the EuRoC header; fix: use [rad s^-1] and [m s^-2]");
  }
}

}  // namespace

Recording read_euroc(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!in || !std::getline(in, line)) throw InputError(source + ": cannot read the EuRoC header; fix: check the file");
  std::string_view header = line;
  if (header.starts_with("\xEF\xBB\xBF")) header.remove_prefix(3);
  header.remove_prefix(1);  // '#'
  std::vector<std::pair<std::string, Unit>> columns;
  while (!header.empty()) {
    const auto comma = header.find(',');
    const std::string_view field = trim(header.substr(0, comma));
    header = comma == std::string_view::npos ? std::string_view{} : header.substr(comma + 1);
    const auto open = field.find('[');
    const auto close = field.rfind(']');
    if (open == std::string_view::npos || close == std::string_view::npos || close < open) {
      throw InputError(source + ":1: EuRoC header field '" + std::string(field) +
                       "' has no [unit]; fix: write it as e.g. 'w_RS_S_x [rad s^-1]'");
    }
    columns.emplace_back(std::string(trim(field.substr(0, open))),
                         euroc_unit(field.substr(open + 1, close - open - 1), source));
  }
  // w_RS_S_{x,y,z} are angular rates, a_RS_S_{x,y,z} specific forces (sensor frame S).
  auto channel_name = [](const std::string& name) -> std::string {
    if (name.size() == 8 && name.starts_with("w_RS_S_")) return "gyro_" + name.substr(7);
    if (name.size() == 8 && name.starts_with("a_RS_S_")) return "accel_" + name.substr(7);
    return name;
  };
  if (columns.size() < 2 || columns[0].second.quantity != Quantity::time) {
    throw InputError(source + ":1: the EuRoC header must start with '#timestamp [ns]' and name at least one data column; fix: restore the header");
  }
  Recording r;
  r.source = source;
  r.format = RecordingFormat::euroc;
  for (std::size_t k = 1; k < columns.size(); ++k) {
    TextReadOptions options;
    options.column = k;
    options.time_column = std::size_t{0};
    options.time_unit = columns[0].second;
    TextColumns text = read_text_file(path, options);
    if (text.column_count != columns.size()) {
      throw InputError(source + ":" + std::to_string(text.first_data_line) + ": rows have " +
                       std::to_string(text.column_count) + " fields but the header names " +
                       std::to_string(columns.size()) + "; fix: make the header and rows agree");
    }
    if (k == 1) {
      r.time_s = std::move(text.time_s);
      r.time_origin = text.time_origin + " " + columns[0].second.name;
    }
    r.channels.push_back(Channel{channel_name(columns[k].first), columns[k].second, std::move(text.values)});
  }
  return r;
}

}  // namespace imunoise::io
