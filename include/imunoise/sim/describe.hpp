#pragma once
// What a simulated record holds, in words: the header of `imunoise simulate`'s files (the rate
// line the loader reads back, the unit, each channel's noise model with its customary units).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "imunoise/sim/generator.hpp"
#include "imunoise/units.hpp"

namespace imunoise::sim {

/// One channel's noise model and output stage ("N 0.0009 deg/sqrt(s), B ..."); "no noise".
std::string describe_channel(const ChannelGenerator& generator, const std::string& unit);

/// Q N B K R of a gyro model in customary units (arcsec, deg/sqrt(h), deg/h, ...); "" for other
/// quantities.
std::string customary_coefficients(const NoiseModel& model, const Unit& unit);

/// The "# ..." header lines: generator, rate and length, unit, format, each channel.
std::string simulation_header(const Generator& generator, const std::string& preset, std::uint64_t seed,
                              const std::string& unit, const std::string& output_unit,
                              const std::string& format);

/// How samples are written: text (one frame a line, channels tab-separated, each value the
/// shortest text that reads back to the same double) or raw little-endian floats, channels
/// interleaved.
enum class SampleFormat { text, f64, f32 };

/// Generates every frame and hands the encoded bytes to `write` chunk by chunk (bounded memory).
void write_samples(Generator& generator, SampleFormat format, unsigned threads,
                   const std::function<void(const void* data, std::size_t bytes)>& write);

}  // namespace imunoise::sim
