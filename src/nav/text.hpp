#pragma once
// Internal: numbers in the assumption strings (the library does not depend on fmt).
#include <cstdio>
#include <string>

namespace imunoise::nav::detail {

/// Shortest-ish "%.6g" text of v.
inline std::string g6(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

}  // namespace imunoise::nav::detail
