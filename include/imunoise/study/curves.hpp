#pragma once
// The deviation-curve stage: the estimators a user asked for, on one record, with noise
// identification, EDF and confidence bounds, kept to a time budget; and the curves as the
// JSON, CSV and text documents of `imunoise dev` (the same JSON is each channel's "curves" in
// the study report).
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/study/record.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"

namespace imunoise::study {

struct CurveOptions {
  std::vector<Estimator> estimators{Estimator::oadev};
  TauGrid grid;                      ///< default: octave
  double ci_level = 0.683;
  bool no_ci = false;                ///< skip noise identification and bounds
  std::optional<int> forced_alpha;   ///< force the power-law noise type
  bool bias_correct = false;         ///< add "<name>-bc" copies of the total/theo curves
  unsigned threads = 0;              ///< 0: all cores
  double time_budget_s = 300.0;      ///< per slow estimator (work_budget.hpp); 0: no limit
  TheoBrRatios theobr_ratios = TheoBrRatios::taylor_howe;
  std::string theobr_ratios_name = "taylor-howe";  ///< as the user wrote it, for the note
};

struct Curve {
  Estimator estimator = Estimator::oadev;
  std::string label;                         ///< estimator name; "<name>-bc" when bias-corrected
  std::vector<DevPoint> points;              ///< dev and bounds in `unit` (not SI)
  std::string unit;
  std::vector<PointConfidence> confidence;   ///< empty with no_ci
  std::vector<std::size_t> skipped;          ///< factors left out by the time budget
  std::string note;                          ///< why, and how to get them; or how it was computed
  std::optional<TheoBiasFactor> theobr_factor;
};

/// Curves of deviations already computed in SI (merged from the slices of `--mpi`): each put in
/// the record's unit, with confidence unless options.no_ci, the noise type identified on
/// `identification_phase_si` (a part of the record) and the EDF counting all `n_phase_total`
/// phase samples. `points[i]` belongs to options.estimators[i]; `note` goes on every curve.
std::vector<Curve> curves_from_points(const Record& record, const CurveOptions& options,
                                      const std::vector<std::vector<DevPoint>>& points_si,
                                      std::span<const double> identification_phase_si, std::size_t n_phase_total,
                                      const std::string& note);

/// Computes every requested curve. Throws InputError when the record is too short for an
/// estimator or an option is invalid. `warn` receives each budget note as it is decided (the
/// CLI prints them on stderr); it may be empty.
std::vector<Curve> compute_curves(const Record& record, const CurveOptions& options,
                                  const std::function<void(const std::string&)>& warn = {});

/// One JSON object per curve (docs: `imunoise dev --format json`); absent numbers are null.
nlohmann::json curve_json(const Record& record, const Curve& curve);
/// All curves as an array.
nlohmann::json curves_json(const Record& record, const std::vector<Curve>& curves);
/// `dev --format csv`: estimator,m,tau_s,dev,unit,n,edf,ci_low,ci_high,alpha.
std::string curves_csv(const std::vector<Curve>& curves);
/// `dev --format table`: a header on the record, then one table per curve with its notes.
std::string curves_table(const Record& record, const std::vector<Curve>& curves, double level);

}  // namespace imunoise::study
