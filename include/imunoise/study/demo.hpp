#pragma once
// The bundled demonstration: the paper's study on simulated data with known truth. Four
// TG-100 gyros with the coefficients of the paper's Table 2 (sim/presets.hpp), 200 Hz, 6 h,
// a fixed seed, in the tetrahedral redundant geometry, studied against the tg100 datasheet.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/study/record.hpp"
#include "imunoise/study/study.hpp"

namespace imunoise::study {

struct DemoOptions {
  double duration_s = 6.0 * 3600.0;
  std::uint64_t seed = 20180614;  ///< fixed: the demo is the same on every machine
  unsigned threads = 0;           ///< simulation threads (0: all cores)
};

/// The four simulated gyros as study records (deg/s), named gyro1..gyro4.
std::vector<Record> simulate_demo_records(const DemoOptions& options);

/// The study options of the demo: tg100 datasheet, tetrahedral geometry, 1 h navigation.
StudyOptions demo_study_options();

/// The paper's Table 2 beside the simulated truth and the recovered values (deg, deg/sqrt(s),
/// deg/s, deg/s/sqrt(s)), with the recovered intervals: {"title", "rows": [...], "markdown",
/// "html"}; added to the document as "reference" so the report shows it.
nlohmann::json demo_reference(const Study& study, const DemoOptions& options);

/// The summary the demo prints: Table 2 recovered / paper / truth, the datasheet comparison,
/// the 1-hour navigation errors beside the paper's, and why they differ.
std::string demo_summary(const nlohmann::json& doc);

}  // namespace imunoise::study
