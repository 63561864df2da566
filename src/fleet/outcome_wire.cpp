#include "imunoise/fleet/outcome_wire.hpp"

#include <cstring>

#include <fmt/core.h>

namespace imunoise::fleet {

std::vector<std::uint8_t> encode_outcome(std::size_t index, const SensorOutcome& outcome) {
  const std::string text = outcome.fit.is_null() ? "E" + outcome.error : "J" + outcome.fit.dump();
  std::vector<std::uint8_t> bytes(8 + text.size());
  const auto i = static_cast<std::uint64_t>(index);
  std::memcpy(bytes.data(), &i, 8);
  std::memcpy(bytes.data() + 8, text.data(), text.size());
  return bytes;
}

std::size_t decode_outcome(std::span<const std::uint8_t> bytes, std::span<const std::string> files,
                           SensorOutcome& outcome) {
  std::uint64_t index = 0;
  std::memcpy(&index, bytes.data(), 8);
  const std::string text(bytes.begin() + 8, bytes.end());
  outcome.file = files[index];
  if (text.front() == 'J') {
    outcome.fit = nlohmann::json::parse(text.substr(1));
  } else {
    outcome.fit = nullptr;
    outcome.error = text.substr(1);
  }
  return index;
}

std::string summary_line(const nlohmann::json& fleet) {
  const auto& summary = fleet["summary"];
  std::string pass = "no datasheet (--spec)";
  if (!summary["datasheet"].is_null()) {
    pass = fmt::format("{} of {} pass {} ({:.0f} %)", summary["datasheet"]["n_pass"].get<std::size_t>(),
                       summary["datasheet"]["n_judged"].get<std::size_t>(),
                       summary["datasheet"]["spec"].get<std::string>(),
                       100.0 * summary["datasheet"]["pass_rate"].get<double>());
  }
  return fmt::format("{} files, {} analysed, {} failed; {}; {} outliers", summary["n_files"].get<std::size_t>(),
                     summary["n_analysed"].get<std::size_t>(), summary["n_failed"].get<std::size_t>(), pass,
                     summary["outliers"].size());
}

}  // namespace imunoise::fleet
