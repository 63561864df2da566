#pragma once
// The fused recording of a redundant unit as CSV (t_s,x,y,z,p1..pk in `unit`), with a header
// line the loader reads back (t_s is recognised as the time column).
#include <string>

#include "imunoise/redundant/fusion.hpp"
#include "imunoise/units.hpp"

namespace imunoise::redundant {

/// Writes without holding the text in memory: rows are formatted in parallel blocks (`threads`,
/// 0 = all cores) into a temporary file renamed at the end, never replacing an existing file
/// unless `force`. InputError naming the file when it exists or cannot be written.
void write_fused_csv(const std::string& path, bool force, const FusedRecord& fused, const Unit& unit,
                     const std::string& geometry, unsigned threads);

}  // namespace imunoise::redundant
