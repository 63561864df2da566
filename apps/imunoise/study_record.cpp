#include "study_record.hpp"

namespace imunoise::cli {

study::Record to_study_record(PhaseRecord&& record, std::string name) {
  study::Record r;
  r.name = name.empty() ? record.source : std::move(name);
  r.source = std::move(record.source);
  r.kind = record.kind;
  r.rate_hz = record.rate_hz;
  r.n_samples = record.n_samples;
  r.phase_si = std::move(record.phase_si);
  r.rate_unit = record.rate_unit;
  r.unit_given = record.unit_given;
  r.timing = std::move(record.timing);
  r.segments = std::move(record.segments);
  r.rate_si = std::move(record.rate_si);
  r.davar = std::move(record.davar);
  if (!record.channel.empty()) {
    r.table_notes.push_back(record.format + ": " + (record.stream.empty() ? "" : record.stream + " ") +
                            "channel " + record.channel);
  }
  for (const auto& line : record.preprocessing) r.table_notes.push_back("preprocessing: " + line);
  return r;
}

}  // namespace imunoise::cli
