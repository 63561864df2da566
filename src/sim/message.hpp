#pragma once
// Small helpers to build InputError messages in src/sim (the library does not link fmt).
#include <cstdio>
#include <string>

namespace imunoise::sim::detail {

/// A number as a user would type it: up to 10 significant digits, no trailing zeros.
inline std::string num(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

}  // namespace imunoise::sim::detail
