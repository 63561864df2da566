#include "mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

#include "imunoise/error.hpp"

#ifndef MADV_POPULATE_READ
#define MADV_POPULATE_READ 22  // Linux 5.14; older kernels refuse it and the pages fault in as before
#endif

namespace imunoise::io {
namespace {
// How far ahead of the reader the pages are mapped, half of it at a time. A read fault maps 16
// pages at most, and on a virtual machine each fault is an exit to the hypervisor: ~950 faults
// of ~26 us for an 80 MB file on the 2-vCPU VM of 2026-12-05 (docs/performance.md). A window,
// not the whole file, so that resident memory stays flat for files of gigabytes.
constexpr std::size_t kPopulateAhead = std::size_t{16} << 20;
}  // namespace

MappedFile::MappedFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path.string() + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw InputError(path.string() + ": not a regular file; fix: give the path of a regular file");
  }
  size_ = static_cast<std::size_t>(st.st_size);
  if (size_ > 0) {
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (p == MAP_FAILED) {
      ::close(fd);
      throw InputError(path.string() + ": cannot map the file: " + std::strerror(errno));
    }
    // Read front to back once: ask the kernel to read ahead aggressively.
    ::madvise(p, size_, MADV_SEQUENTIAL);
    ::madvise(p, size_, MADV_WILLNEED);
    data_ = static_cast<const unsigned char*>(p);
  }
  ::close(fd);
}

void MappedFile::populate_ahead(std::size_t from) {
  const std::size_t end = std::min(size_, from + kPopulateAhead);
  if (populated_ >= size_ || populated_ >= std::min(size_, from + kPopulateAhead / 2)) return;
  static const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t begin = std::max(populated_, from) / page * page;
  if (end > begin) ::madvise(const_cast<unsigned char*>(data_) + begin, end - begin, MADV_POPULATE_READ);
  populated_ = end;
}

MappedFile::~MappedFile() {
  if (data_ != nullptr) ::munmap(const_cast<unsigned char*>(data_), size_);
}

void MappedFile::release_before(std::size_t end) {
  static const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  // In steps of at least 1 MB: a reader that takes 64 KB blocks would otherwise make a system
  // call per block (and the kernel's read-ahead works in larger units anyway).
  constexpr std::size_t kStep = std::size_t{1} << 20;
  const std::size_t upto = std::min(end, size_) / page * page;
  if (upto > released_ && (upto - released_ >= kStep || end >= size_)) {
    ::madvise(const_cast<unsigned char*>(data_) + released_, upto - released_, MADV_DONTNEED);
    released_ = upto;
  }
  populate_ahead(end);
}

}  // namespace imunoise::io
