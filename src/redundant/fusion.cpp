#include "imunoise/redundant/fusion.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::redundant {
namespace {

// Tile of samples kept in L1 while the n inputs are accumulated into one output row.
constexpr std::size_t kTile = 512;

}  // namespace

void apply_rows(const Matrix& m, std::span<const std::span<const double>> sensors,
                std::span<const std::span<double>> out) {
  const std::size_t n = sensors.size();
  if (n != m.cols || out.size() > m.rows) {
    throw InputError(fmt::format("apply_rows: {} inputs for a {} x {} matrix", n, m.rows, m.cols));
  }
  const std::size_t len = n ? sensors[0].size() : 0;
  alignas(64) double tile[kTile];
  for (std::size_t t0 = 0; t0 < len; t0 += kTile) {
    const std::size_t w = std::min(kTile, len - t0);
    for (std::size_t r = 0; r < out.size(); ++r) {
      const double c0 = m(r, 0);
      const double* x0 = sensors[0].data() + t0;
#pragma omp simd
      for (std::size_t u = 0; u < w; ++u) tile[u] = c0 * x0[u];
      for (std::size_t i = 1; i < n; ++i) {
        const double c = m(r, i);
        const double* x = sensors[i].data() + t0;
#pragma omp simd
        for (std::size_t u = 0; u < w; ++u) tile[u] += c * x[u];
      }
      std::copy(tile, tile + w, out[r].data() + t0);
    }
  }
}

namespace {

void check_records(const Analysis& analysis, std::span<const std::span<const double>> sensors, double rate_hz) {
  const std::size_t n = analysis.geometry.size();
  if (sensors.size() != n) {
    throw InputError(fmt::format("{} recordings for the {} sensors of geometry {}: give one per "
                                 "sensing axis, in order", sensors.size(), n, analysis.geometry.name));
  }
  const std::size_t len = sensors[0].size();
  for (std::size_t i = 0; i < n; ++i) {
    if (sensors[i].size() != len) {
      throw InputError(fmt::format("recording {} has {} samples, recording 1 has {}: the "
                                   "recordings must be synchronous (equal length)", i + 1,
                                   sensors[i].size(), len));
    }
  }
  if (!(rate_hz > 0) || !std::isfinite(rate_hz)) {
    throw InputError(fmt::format("the sample rate must be positive and finite, got {} Hz", rate_hz));
  }
}

}  // namespace

std::optional<DetectionResult> fuse_into(const Analysis& analysis,
                                         std::span<const std::span<const double>> sensors,
                                         double rate_hz, const FusionOptions& options,
                                         std::span<const std::span<double>> axes_out,
                                         std::span<const std::span<double>> parity_out) {
  check_records(analysis, sensors, rate_hz);
  const std::size_t len = sensors[0].size();
  if (axes_out.size() != 3 || (!parity_out.empty() && parity_out.size() != analysis.parity.rows)) {
    throw InputError(fmt::format("fuse_into: 3 axis outputs and 0 or {} parity outputs, got {} and {}",
                                 analysis.parity.rows, axes_out.size(), parity_out.size()));
  }
  for (const auto& o : axes_out) if (o.size() != len) throw InputError("fuse_into: an output's length differs from the records'");
  for (const auto& o : parity_out) if (o.size() != len) throw InputError("fuse_into: an output's length differs from the records'");
  std::optional<FaultDetector> detector;
  if (options.detect) detector.emplace(analysis.geometry, analysis.sensors, rate_hz, options.detection);
  const std::size_t k = parity_out.size();

  // Time slices fused in parallel; detection (sequential by nature, n additions a sample) runs
  // on its own thread meanwhile.
  const unsigned threads = std::max(1u, options.threads);
  auto fuse_slice = [&](std::size_t t0, std::size_t t1) {
    std::vector<std::span<const double>> in;
    for (const auto& s : sensors) in.push_back(s.subspan(t0, t1 - t0));
    std::vector<std::span<double>> axes;
    for (const auto& a : axes_out) axes.push_back(a.subspan(t0, t1 - t0));
    apply_rows(analysis.fusion, in, axes);
    if (k) {
      std::vector<std::span<double>> par;
      for (const auto& p : parity_out) par.push_back(p.subspan(t0, t1 - t0));
      apply_rows(analysis.parity, in, par);
    }
  };
  std::vector<std::thread> workers;
  std::exception_ptr detector_error;
  if (detector && threads > 1) {
    workers.emplace_back([&] {
      try {
        detector->push(sensors);
      } catch (...) {
        detector_error = std::current_exception();
      }
    });
  }
  const std::size_t slices = threads;
  const std::size_t per = (len + slices - 1) / slices;
  for (std::size_t s = 1; s < slices; ++s) {
    const std::size_t t0 = std::min(len, s * per), t1 = std::min(len, (s + 1) * per);
    if (t1 > t0) workers.emplace_back(fuse_slice, t0, t1);
  }
  fuse_slice(0, std::min(len, per));
  if (detector && threads == 1) detector->push(sensors);
  for (auto& w : workers) w.join();
  if (detector_error) std::rethrow_exception(detector_error);
  if (detector) return detector->result();
  return std::nullopt;
}

FusedRecord fuse_records(const Analysis& analysis, std::span<const std::span<const double>> sensors,
                         double rate_hz, const FusionOptions& options) {
  check_records(analysis, sensors, rate_hz);
  const std::size_t len = sensors[0].size();
  FusedRecord out;
  out.rate_hz = rate_hz;
  out.samples = len;
  for (auto& a : out.axes_rad_s) a.resize(len);
  const std::size_t k = options.parity ? analysis.parity.rows : 0;
  out.parity_rad_s.assign(k, std::vector<double>(len));
  std::vector<std::span<double>> axes, parity;
  for (auto& a : out.axes_rad_s) axes.emplace_back(a);
  for (auto& p : out.parity_rad_s) parity.emplace_back(p);
  out.detection = fuse_into(analysis, sensors, rate_hz, options, axes, parity);
  return out;
}

}  // namespace imunoise::redundant
