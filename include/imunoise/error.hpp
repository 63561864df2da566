#pragma once
// The library's one exception type: the input or an argument is invalid.
#include <stdexcept>
#include <string>

namespace imunoise {

/// Thrown where input is checked. what() names the offending file, line, sample or option
/// and says how to fix it; the CLI prints it verbatim and exits with status 1.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace imunoise
