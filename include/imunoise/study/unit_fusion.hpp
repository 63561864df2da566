#pragma once
// The recordings of a redundant unit (one per sensor, in the geometry's order) fused into body
// axes and parity residuals, with fault detection on request: the checks that make the
// recordings one unit (one rate, one length), each sensor's noise model (given, or fitted from
// its own recording by the one Record fit), the unit's analysis and the fusion.
#include <span>
#include <string>
#include <vector>

#include "imunoise/load/record.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/fusion.hpp"

namespace imunoise::study {

struct FusedUnit {
  redundant::Analysis analysis;
  redundant::FusedRecord fused;
  std::vector<std::string> notes;  ///< what was decided: recordings trimmed, models fitted
};

/// `recordings` must keep their rates (LoadOptions::keep_rates). Without `models` and with
/// fusion.detect, each sensor's model is fitted from its recording. InputError when the
/// recordings are not synchronous or a model cannot be fitted.
FusedUnit fuse_recordings(const redundant::Geometry& geometry, std::vector<Record> recordings,
                          std::vector<redundant::SensorModel> models, const redundant::AnalysisOptions& analysis,
                          const redundant::FusionOptions& fusion);

/// InputError naming the first record whose values have no angular-rate unit (a text or
/// binary file read without --units), and the fix; `option` names what needs them.
void require_angular_rates(std::span<const Record> records, const std::string& option);

}  // namespace imunoise::study
