#pragma once
// Output that never silently replaces a file: written chunk by chunk to a temporary file beside
// the target and renamed over it only on commit(), or to standard output ("" or "-"). Nothing
// is left behind when the writer is destroyed without commit() (an error on the way). A target
// that exists and is not a regular file (/dev/null, a FIFO, a terminal) holds no data to lose
// and must never be replaced by a rename: it is written directly.
#include <cstddef>
#include <cstdio>
#include <string>

namespace imunoise::io {

class AtomicOutput {
 public:
  /// InputError when `path` exists and `force` is not set, or cannot be created.
  AtomicOutput(const std::string& path, bool force);
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  ~AtomicOutput();

  /// InputError naming the file when the write fails (disk full, closed pipe).
  void write(const void* data, std::size_t bytes);
  /// Renames the temporary file over the target (flushes standard output).
  void commit();

 private:
  std::string path_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
  bool direct_ = false;  // written in place (a device or FIFO), nothing to rename or remove
};

}  // namespace imunoise::io
