#pragma once
// The datasheet comparison as a JSON document: the `spec_comparison` object of
// `imunoise fit --format json` and of Python's imunoise.fit(..., spec=...).
#include <nlohmann/json.hpp>

#include "imunoise/spec/comparison.hpp"

namespace imunoise {

/// spec, source, sensor, confidence_level, rule, all_pass and, per term: measured (SI and
/// customary), measured in the spec's unit, spec value/unit/psd/tolerance/limit, deviation
/// percent, verdict, ci_vs_limit, conclusive, note. Absent numbers are null.
nlohmann::json comparison_json(const SpecComparison& comparison);

}  // namespace imunoise
