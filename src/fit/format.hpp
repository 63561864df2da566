#pragma once
// printf-style formatting for the fit module's notes and messages (the library does not
// depend on fmt). Internal to the fit module.
#include <string>

namespace imunoise::fit::detail {

std::string strf(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace imunoise::fit::detail
