#pragma once
// Fusion of n synchronous sensor recordings into body-axis rates w^ = G m and parity residuals
// p = V m (analysis.hpp), with optional fault detection (detection.hpp) in the same pass.
//
// Cost: (3 + k) n multiply-adds per frame plus n additions for detection; memory-bound.
// Measured (bench/bench_redundant.cpp): see docs/performance.md.
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/detection.hpp"

namespace imunoise::redundant {

struct FusionOptions {
  bool detect = false;            ///< run fault detection (needs the sensors' models)
  DetectionOptions detection;
  bool parity = true;             ///< also return the parity residuals
  unsigned threads = 1;           ///< worker threads (results do not depend on it)
};

/// Fused output of a whole record, SI.
struct FusedRecord {
  double rate_hz = 0.0;
  std::size_t samples = 0;
  std::array<std::vector<double>, 3> axes_rad_s;  ///< fused body rates x, y, z
  std::vector<std::vector<double>> parity_rad_s;  ///< p_1..p_k (empty unless options.parity)
  std::optional<DetectionResult> detection;
};

/// Writes out[r][t] = sum_i m(r, i) sensors[i][t] for every row r of m (rows = out.size()):
/// the fusion (m = G) or the parity (m = V) of a slice. All spans of equal length.
void apply_rows(const Matrix& m, std::span<const std::span<const double>> sensors,
                std::span<const std::span<double>> out);

/// Fuses into caller-owned outputs (3 axis spans and either no parity span or k of them, all
/// of the records' length, rad/s): lets a caller reuse buffers or map a file. Returns the
/// detection result when options.detect. Same checks as fuse_records.
std::optional<DetectionResult> fuse_into(const Analysis& analysis,
                                         std::span<const std::span<const double>> sensors_rad_s,
                                         double rate_hz, const FusionOptions& options,
                                         std::span<const std::span<double>> axes_out,
                                         std::span<const std::span<double>> parity_out);

/// Fuses whole records (one span per sensor, rad/s, equal lengths, in the geometry's order).
/// InputError for a count or length mismatch, or detection without models.
FusedRecord fuse_records(const Analysis& analysis, std::span<const std::span<const double>> sensors_rad_s,
                         double rate_hz, const FusionOptions& options = {});

}  // namespace imunoise::redundant
