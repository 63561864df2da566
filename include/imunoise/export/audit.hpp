#pragma once
// The parameter audit: each value of a user's filter file against what the recording measures,
// with the measurement's interval, classified as
//   consistent       inside the interval of the value imunoise would write;
//   inflated x k     larger by k beyond the interval (a common, deliberate margin for
//                    unmodelled effects; reported, not an error);
//   too small x k    smaller than the interval: the filter is over-confident (an error);
//   a mistake        the value matches, within the interval, a recognisable slip:
//                    x sqrt(rate) / / sqrt(rate) (a discrete per-sample value where a density
//                    belongs, or the reverse), deg for rad / rad for deg, sigma for sigma^2 /
//                    sigma^2 for sigma, PX4's IMU rate for its EKF rate;
//   not checked      the recording does not identify the term (or has no such sensor).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/export/export_model.hpp"
#include "imunoise/export/read_params.hpp"

namespace imunoise::exports {

enum class Verdict { consistent, inflated, too_small, mistake, not_checked };

std::string_view verdict_name(Verdict v);  ///< "consistent", "inflated", "too_small", "mistake", "not_checked"

struct AuditItem {
  ParamValue param;
  Verdict verdict = Verdict::not_checked;
  double expected = 0.0;   ///< the value imunoise would write (file units)
  double low = 0.0;        ///< its interval (the fit's level), file units
  double high = 0.0;
  double ratio = 0.0;      ///< file / expected
  std::string mistake;     ///< for Verdict::mistake: "x sqrt(rate) (...)"
  std::string message;     ///< one sentence for the user
};

struct AuditResult {
  std::string path;
  Target target;
  double rate_hz = 0.0;
  std::vector<AuditItem> items;
  std::vector<std::string> notes;  ///< the file's own rate differing from the recording's, missing keys
  bool ok = true;                  ///< no mistake and nothing too small
};

/// Audits `file` against the measured model (its rate is the recording's).
AuditResult audit(const ParamsFile& file, const ExportModel& measured);

/// {"file", "target", "rate_hz", "ok", "notes", "values": [{"key", "sensor", "term", "unit",
///  "value", "expected", "interval": [low, high], "ratio", "verdict", "mistake", "message"}]}
nlohmann::json audit_json(const AuditResult& result);

/// A table for people, one line per value, and the overall verdict.
std::string audit_table(const AuditResult& result);

}  // namespace imunoise::exports
