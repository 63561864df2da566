#include "imunoise/spec/report.hpp"

#include <cmath>
#include <string>

namespace imunoise {
namespace {

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json value_json(const ValueInUnit& v) {
  return {{"value", number(v.value)},
          {"ci_low", number(v.ci_low)},
          {"ci_high", number(v.ci_high)},
          {"unit", v.unit}};
}

}  // namespace

nlohmann::json comparison_json(const SpecComparison& comparison) {
  nlohmann::json j;
  j["spec"] = comparison.spec_name;
  j["source"] = comparison.spec_source;
  j["sensor"] = std::string(sensor_kind_name(comparison.sensor));
  j["confidence_level"] = comparison.confidence_level;
  j["rule"] =
      "pass if measured <= spec * (1 + tolerance); deviation_percent = "
      "100 * (measured / spec - 1); conclusive if the whole confidence interval lies "
      "on the verdict's side of the limit";
  j["all_pass"] = comparison.all_pass;
  auto terms = nlohmann::json::array();
  for (const auto& r : comparison.rows) {
    nlohmann::json t;
    t["term"] = r.term;
    t["symbol"] = std::string(1, r.symbol);
    t["title"] = r.title;
    t["identified"] = r.identified;
    t["measured"] = value_json(r.measured_si);
    t["measured_customary"] = value_json(r.measured_customary);
    if (r.verdict != Verdict::not_in_spec) {
      t["measured_in_spec_unit"] = value_json(r.measured_spec_unit);
      t["spec"] = {{"value", number(r.spec_value)},
                   {"unit", r.spec_unit},
                   {"psd", r.psd},
                   {"tolerance", r.tolerance},
                   {"limit", number(r.spec_value * (1.0 + r.tolerance))}};
      t["spec_si"] = {{"value", number(r.spec_si)},
                      {"limit", number(r.limit_si)},
                      {"unit", r.measured_si.unit}};
    }
    t["deviation_percent"] = number(r.deviation_percent);
    t["verdict"] = std::string(verdict_name(r.verdict));
    t["ci_vs_limit"] = std::string(ci_position_name(r.ci_position));
    t["conclusive"] = r.conclusive;
    if (!r.note.empty()) t["note"] = r.note;
    terms.push_back(std::move(t));
  }
  j["terms"] = std::move(terms);
  return j;
}

}  // namespace imunoise
