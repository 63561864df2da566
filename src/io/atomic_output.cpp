#include "imunoise/io/atomic_output.hpp"

#include <filesystem>
#include <system_error>

#include "imunoise/error.hpp"

namespace imunoise::io {

AtomicOutput::AtomicOutput(const std::string& path, bool force) : path_(path) {
  if (path.empty() || path == "-") {
    file_ = stdout;
    return;
  }
  namespace fs = std::filesystem;
  std::error_code status_error;
  const fs::file_status status = fs::status(path, status_error);
  if (fs::is_directory(status)) {
    throw InputError(path + ": is a directory; -o needs a file name");
  }
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    file_ = std::fopen(path.c_str(), "wb");
    if (!file_) throw InputError(path + ": cannot open it for writing");
    direct_ = true;
    return;
  }
  if (fs::exists(status) && !force) {
    throw InputError(path + ": file exists; imunoise does not overwrite it — choose another -o name "
                     "or pass --force");
  }
  temporary_ = path + ".imunoise-tmp";
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (!file_) throw InputError(path + ": cannot create the file; check the directory");
}

AtomicOutput::~AtomicOutput() {
  if (file_ && file_ != stdout) {
    std::fclose(file_);
    if (direct_) return;
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);  // not committed: leave nothing behind
  }
}

void AtomicOutput::write(const void* data, std::size_t bytes) {
  if (bytes != 0 && std::fwrite(data, 1, bytes, file_) != bytes) {
    throw InputError((file_ == stdout ? std::string("standard output") : path_) +
                     ": write failed (disk full or closed pipe?)");
  }
}

void AtomicOutput::commit() {
  if (file_ == stdout) {
    std::fflush(stdout);
    return;
  }
  const bool ok = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!ok) throw InputError(path_ + ": write failed (disk full?)");
  if (!direct_) std::filesystem::rename(temporary_, path_);
}

}  // namespace imunoise::io
