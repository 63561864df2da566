#include "imunoise/series.hpp"

#include <string>

#include "imunoise/error.hpp"

namespace imunoise {

InputKind parse_input_kind(std::string_view text) {
  if (text == "rate" || text == "freq") return InputKind::rate;
  if (text == "angle" || text == "phase") return InputKind::angle;
  throw InputError("unknown input kind '" + std::string(text) +
                   "'; use rate (alias freq) or angle (alias phase)");
}

std::string_view input_kind_name(InputKind kind) {
  return kind == InputKind::rate ? "rate" : "angle";
}

}  // namespace imunoise
