#include "format.hpp"

#include <cstdarg>
#include <cstdio>

namespace imunoise::fit::detail {

std::string strf(const char* format, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  return buffer;
}

}  // namespace imunoise::fit::detail
