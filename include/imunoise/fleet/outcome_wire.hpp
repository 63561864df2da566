#pragma once
// One sensor's outcome as bytes, for the ranks of a parallel fleet run: the file's index, then
// either the error message, or the summary (doubles as their 8 bytes, so they arrive exactly)
// and the fit document as JSON text (doubles to 17 digits, so it reads back to the same values).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "imunoise/fleet/fleet.hpp"

namespace imunoise::fleet {

std::vector<std::uint8_t> encode_outcome(std::size_t index, const SensorOutcome& outcome);

/// The index the bytes carry, and the outcome with its file taken from `files`. InputError for
/// bytes that are not an encoded outcome (truncated, an index outside `files`).
std::size_t decode_outcome(std::span<const std::uint8_t> bytes, std::span<const std::string> files,
                           SensorOutcome& outcome);

/// The one-line summary a fleet run prints: files, analysed, failed, pass rate, outliers.
std::string summary_line(const nlohmann::json& fleet);

}  // namespace imunoise::fleet
