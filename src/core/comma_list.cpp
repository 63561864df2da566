#include "imunoise/comma_list.hpp"

namespace imunoise {
namespace {

std::string_view strip_blanks(std::string_view text) {
  constexpr std::string_view blanks = " \t";
  const auto first = text.find_first_not_of(blanks);
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(blanks) - first + 1);
}

}  // namespace

std::vector<std::string> split_comma_list(std::string_view text) {
  std::vector<std::string> items;
  if (strip_blanks(text).empty()) return items;
  while (true) {
    const auto comma = text.find(',');
    items.emplace_back(strip_blanks(text.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return items;
}

}  // namespace imunoise
