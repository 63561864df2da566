#pragma once
// One recorded channel as every stage after loading sees it: angle (phase) samples in SI with
// the rate, the unit the user reads results in, and where it came from (the file, the channel,
// what preprocessing removed). load() (load/load.hpp) makes it from a file; the demo, the
// simulator and Python make it from arrays (load/integrate.hpp).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/io/timestamps.hpp"
#include "imunoise/preprocess/dynamic_allan.hpp"
#include "imunoise/preprocess/preprocess.hpp"
#include "imunoise/preprocess/temperature.hpp"
#include "imunoise/series.hpp"
#include "imunoise/units.hpp"

namespace imunoise {

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

  // Provenance: what was read and what was done to it.
  std::string format;            ///< container read ("text", "binary", "ROS 1 bag", "MCAP", ...)
  std::string stream;            ///< topic or dataset read, when the container has several
  std::string channel;           ///< channel read (e.g. "gyro_x"), when the container names them
  /// One line per preprocessing step: what was removed and how much.
  std::vector<std::string> preprocessing;
  /// What the loader decided on the user's behalf (a rate taken from a file header, ...).
  std::vector<std::string> notes;

  /// A record split at gaps or rejected outliers (--gaps split, --outliers reject): the index
  /// ranges analysed as independent segments, and the rate samples (SI) their pooled oadev is
  /// computed from (preprocess.hpp). Empty for a contiguous record.
  std::vector<preprocess::Segment> segments;
  std::vector<double> rate_si;
  /// The dynamic Allan variance of the (preprocessed) rates, when asked for (--davar).
  std::optional<preprocess::DavarResult> davar;
  /// Bias and noise per temperature bin, when a temperature channel was given.
  std::vector<preprocess::TemperatureBin> temperature_bins;
};

/// A record of rate samples already in memory and in SI (a simulation, an array from Python):
/// named `name` (also its source), `unit` the unit its deviations are reported in; unit_given
/// false labels them "input unit".
Record rate_record(std::string name, std::vector<double> rate_si, double rate_hz, Unit unit,
                   bool unit_given = true);

/// Label of the record's rate unit (or of its integral, for tdev/mtie-like estimators): its
/// name, or "input unit" (with /s or *s) when none was given.
std::string unit_label(const Record& record, bool integrated = false);

/// True when the unit was given and is an angular rate: customary gyro units apply.
bool is_gyro(const Record& record);

/// Lines printed under the record's header in text tables: the container channel read and
/// each preprocessing step.
std::vector<std::string> table_notes(const Record& record);

}  // namespace imunoise
