#include "imunoise/study/unit_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/study/sensor.hpp"

namespace imunoise::study {

FusedUnit fuse_recordings(const redundant::Geometry& geometry, std::vector<Record> recs,
                          std::vector<redundant::SensorModel> models, const redundant::AnalysisOptions& analysis,
                          const redundant::FusionOptions& fusion) {
  FusedUnit out;
  for (std::size_t i = 1; i < recs.size(); ++i) {
    if (std::abs(recs[i].rate_hz / recs[0].rate_hz - 1.0) > 1e-6) {
      throw InputError(fmt::format("{} is sampled at {:.9g} Hz but {} at {:.9g} Hz: the recordings "
                                   "must be synchronous (resample them first)", recs[i].source,
                                   recs[i].rate_hz, recs[0].source, recs[0].rate_hz));
    }
  }
  std::size_t len = recs[0].rate_si.size();
  for (const auto& r : recs) len = std::min(len, r.rate_si.size());
  for (auto& r : recs) {
    if (r.rate_si.size() != len) {
      out.notes.push_back(fmt::format("{} has {} samples; the shortest recording has {}: its last {} samples "
                                      "are not used", r.source, r.rate_si.size(), len, r.rate_si.size() - len));
      r.rate_si.resize(len);
    }
  }
  if (models.empty() && fusion.detect) {
    out.notes.push_back("no --from fits: each recording's noise model is fitted from the recording itself "
                        "(a fault inside it inflates its model)");
    for (const auto& r : recs) models.push_back(sensor_model(r));
  }
  out.analysis = redundant::analyze_unit(geometry, models, analysis);
  std::vector<std::span<const double>> spans;
  for (const auto& r : recs) spans.emplace_back(r.rate_si);
  out.fused = redundant::fuse_records(out.analysis, spans, recs[0].rate_hz, fusion);
  return out;
}

void require_angular_rates(std::span<const Record> records, const std::string& option) {
  for (const auto& r : records) {
    if (!r.unit_given || r.rate_unit.quantity != Quantity::angular_rate) {
      throw InputError(r.source + ": " + option + " needs the unit of the recordings' values: pass "
                       "--units deg/s (or rad/s, ...)");
    }
  }
}

}  // namespace imunoise::study
