#include "imunoise/load/record.hpp"

namespace imunoise {

Record rate_record(std::string name, std::vector<double> rate_si, double rate_hz, Unit unit, bool unit_given) {
  Record r;
  r.name = r.source = std::move(name);
  r.rate_hz = rate_hz;
  r.n_samples = rate_si.size();
  r.rate_unit = std::move(unit);
  r.unit_given = unit_given;
  r.rate_si = std::move(rate_si);
  return r;
}

std::string unit_label(const Record& record, bool integrated) {
  if (!record.unit_given) {
    const bool angle = record.kind == InputKind::angle;
    if (integrated) return angle ? "input unit" : "input unit*s";
    return angle ? "input unit/s" : "input unit";
  }
  return integrated ? integral_unit(record.rate_unit).name : record.rate_unit.name;
}

bool is_gyro(const Record& record) {
  return record.unit_given && record.rate_unit.quantity == Quantity::angular_rate;
}

std::vector<std::string> table_notes(const Record& record) {
  std::vector<std::string> notes;
  if (!record.channel.empty()) {
    notes.push_back(record.format + ": " + (record.stream.empty() ? "" : record.stream + " ") +
                    "channel " + record.channel);
  }
  for (const auto& line : record.preprocessing) notes.push_back("preprocessing: " + line);
  return notes;
}

}  // namespace imunoise
