#pragma once
// What a sensor record is once read: equally spaced samples of one quantity.
#include <string_view>

namespace imunoise {

/// Whether samples are a rate (gyro rate, specific force, fractional frequency) or its
/// integral (angle, velocity, time error). Time-and-frequency names are aliases:
/// freq = rate, phase = angle.
enum class InputKind { rate, angle };

/// Parses "rate", "freq", "angle" or "phase"; throws InputError otherwise.
InputKind parse_input_kind(std::string_view text);

std::string_view input_kind_name(InputKind kind);

}  // namespace imunoise
