#include "output.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "imunoise/error.hpp"

namespace imunoise::cli {

void write_output(const OutputOptions& options, const std::string& text) {
  if (options.path.empty() || options.path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return;
  }
  namespace fs = std::filesystem;
  const fs::path target(options.path);
  if (fs::exists(target) && !options.force) {
    throw InputError(options.path + ": file exists; imunoise does not overwrite it — choose " +
                     "another -o name or pass --force");
  }
  const fs::path temporary = target.string() + ".imunoise-tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw InputError(options.path + ": cannot create the file; check the directory");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out) throw InputError(options.path + ": write failed (disk full?)");
  }
  fs::rename(temporary, target);
}

}  // namespace imunoise::cli
