#pragma once
// Where a command's report goes: standard output, or a file that is never silently replaced.
#include <string>

namespace imunoise::cli {

struct OutputOptions {
  std::string path;    ///< -o FILE; empty or "-" for standard output
  bool force = false;  ///< --force: replace an existing file
};

/// Writes `text` to the output. An existing file is an InputError unless force is set; the
/// file is written to a temporary name first and renamed, so a failure never leaves half a file.
void write_output(const OutputOptions& options, const std::string& text);

}  // namespace imunoise::cli
