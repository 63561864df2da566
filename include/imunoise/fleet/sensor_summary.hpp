#pragma once
// What the fleet statistics need of one sensor's study, typed and in the units its fit
// document states (so a distribution, a flag's reason and a CSV cell show what the sensor's
// own document shows): the five coefficients with their intervals, the datasheet verdicts, the
// navigation error at the horizon. A missing number is NaN (null in the documents).
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/study/record.hpp"
#include "imunoise/study/sensor.hpp"

namespace imunoise::fleet {

struct TermSummary {
  std::string name;   ///< Q N B K R
  std::string unit;   ///< the document's unit of the coefficient ("deg/sqrt(s)")
  double value = 0.0;
  double ci_low = 0.0;
  double ci_high = 0.0;
  bool identified = false;
  bool fitted = true;  ///< the term was part of the model fitted
};

struct DatasheetTerm {
  std::string symbol;   ///< N B K
  std::string verdict;  ///< pass fail not_identified not_in_spec ...
  double measured = 0.0;             ///< in the spec's unit
  std::string measured_unit;
  double deviation_percent = 0.0;    ///< 100 (measured / spec - 1)
  double spec = 0.0;                 ///< as written in the spec
  std::string spec_unit;
  bool conclusive = false;           ///< the verdict holds over the whole interval
};

struct DatasheetSummary {
  std::string spec;
  bool all_pass = false;
  std::vector<DatasheetTerm> terms;
};

struct SensorSummary {
  double rate_hz = 0.0;
  std::size_t n_samples = 0;
  std::string unit;                    ///< the record's rate unit label
  std::array<TermSummary, 5> terms;    ///< Q N B K R
  std::optional<DatasheetSummary> datasheet;
  std::optional<study::NavAtHorizon> nav;  ///< when asked for (SensorOptions::nav)
};

/// The summary of a sensor's study, the same numbers `study::sensor_json` writes.
SensorSummary summarize(const Record& record, const study::SensorOptions& options, const study::SensorStudy& study);

}  // namespace imunoise::fleet
