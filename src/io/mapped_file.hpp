#pragma once
// A whole file mapped read-only: the container readers parse it in place, the binary reader
// decodes samples straight from it (no copy through read()).
#include <cstddef>
#include <filesystem>
#include <span>

namespace imunoise::io {

/// A whole file mapped read-only (an empty file maps to an empty span). InputError when the
/// file cannot be opened, is not a regular file, or cannot be mapped.
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  [[nodiscard]] std::span<const unsigned char> bytes() const { return {data_, size_}; }
  /// Drops the whole pages before byte `end` from this process (they stay in the page cache),
  /// so that resident memory does not grow with a file read front to back.
  void release_before(std::size_t end);
  /// Sets up the page-table entries of the next few megabytes from byte `from` in one system
  /// call, unless that is already done (release_before calls it: a reader front to back).
  void populate_ahead(std::size_t from);

 private:
  const unsigned char* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t released_ = 0;
  std::size_t populated_ = 0;
};

}  // namespace imunoise::io
