#pragma once
// One recorded channel as every stage of the study sees it: angle (phase) samples in SI with
// the rate, the unit the user reads results in, and where it came from. The command line
// loads files into it (apps/imunoise/input_options), the demo and Python fill it directly.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/io/timestamps.hpp"
#include "imunoise/preprocess/dynamic_allan.hpp"
#include "imunoise/preprocess/preprocess.hpp"
#include "imunoise/series.hpp"
#include "imunoise/units.hpp"

namespace imunoise::study {

struct Record {
  std::string name;              ///< channel name in reports (column header, file stem, "gyro1")
  std::string source;            ///< file name as given ("standard input" for "-")
  InputKind kind = InputKind::rate;
  double rate_hz = 0.0;
  std::size_t n_samples = 0;     ///< samples in the file (rate samples, or angle samples)
  std::vector<double> phase_si;  ///< angle samples in SI (rad, m/s, s or unit*s)
  Unit rate_unit;                ///< unit deviations are reported in
  bool unit_given = false;       ///< false when no unit was given (label "input unit")
  std::optional<io::TimingReport> timing;
  /// A record split at gaps or rejected outliers (--gaps split, --outliers reject): the index
  /// ranges analysed as independent segments, and the rate samples (SI) their pooled oadev is
  /// computed from (preprocess.hpp). Empty for a contiguous record.
  std::vector<preprocess::Segment> segments;
  std::vector<double> rate_si;
  /// The dynamic Allan variance of the (preprocessed) rates, when asked for (--davar): the
  /// report shows it as a heat map with its stationarity verdict.
  std::optional<preprocess::DavarResult> davar;
  /// Lines printed under the record's header in text tables (recording, preprocessing).
  std::vector<std::string> table_notes;
};

/// Label of the record's rate unit (or of its integral, for tdev/mtie-like estimators): its
/// name, or "input unit" (with /s or *s) when none was given.
std::string unit_label(const Record& record, bool integrated = false);

/// True when the unit was given and is an angular rate: customary gyro units apply.
bool is_gyro(const Record& record);

}  // namespace imunoise::study
