#pragma once
// A study's fitted channels as the filter exports take them (export/export_model.hpp): each
// channel's fit on its axis, the sample rate they share, the files they come from.
#include <string>
#include <vector>

#include "imunoise/export/export_model.hpp"
#include "imunoise/study/study.hpp"

namespace imunoise::study {

struct StudyFits {
  std::vector<exports::AxisFit> fits;
  double rate_hz = 0.0;
  std::string sources;  ///< the files, comma separated, each once
};

/// InputError when the fitted channels have different rates (a filter file has one).
StudyFits study_fits(const Study& study);

}  // namespace imunoise::study
