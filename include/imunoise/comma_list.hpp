#pragma once
// Comma lists as users type them on a command line or in Python: "gx, gy,gz".
#include <string>
#include <string_view>
#include <vector>

namespace imunoise {

/// The items of a comma list, each stripped of surrounding blanks. An empty or all-blank text
/// is an empty list; an empty item between commas stays (callers reject it with context).
std::vector<std::string> split_comma_list(std::string_view text);

}  // namespace imunoise
