#pragma once
// Scratch vectors grown with their fresh pages mapped in one system call. Every first touch of
// a fresh page is a fault, and on a virtual machine a fault is an exit to the hypervisor (about
// 26 us each on the 2-vCPU VM of 2026-12-05, docs/performance.md): a megabyte of scratch then
// costs ~7 ms in 256 faults, against well under one in a single MADV_POPULATE_WRITE.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older kernels refuse it and the pages fault in as before
#endif

namespace imunoise::detail {

/// The whole 4 KB pages inside [p, p + bytes): {first, last}, empty when last <= first.
struct PageRange {
  std::uintptr_t first = 0, last = 0;
};
inline PageRange whole_pages(const void* p, std::size_t bytes, std::uintptr_t page = 4096) {
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  return {(begin + page - 1) & ~(page - 1), (begin + bytes) & ~(page - 1)};
}

/// Asks for transparent huge pages on the whole 2 MB pages inside [p, p + bytes) (in madvise
/// mode: one fault and one clear per 2 MB instead of 512). Returns the bytes advised.
inline std::size_t advise_huge_pages(const void* p, std::size_t bytes) {
  const PageRange huge = whole_pages(p, bytes, std::uintptr_t{1} << 21);
  if (huge.last <= huge.first) return 0;
  ::madvise(reinterpret_cast<void*>(huge.first), huge.last - huge.first, MADV_HUGEPAGE);
  return huge.last - huge.first;
}

/// Maps the whole pages inside [p, p + bytes) in one MADV_POPULATE_WRITE (no stores: safe
/// beside a thread that writes them).
inline void populate_pages(const void* p, std::size_t bytes) {
  const PageRange pages = whole_pages(p, bytes);
  if (pages.last > pages.first) {
    ::madvise(reinterpret_cast<void*>(pages.first), pages.last - pages.first, MADV_POPULATE_WRITE);
  }
}

/// Maps the whole pages inside [p, p + bytes) before they are written: huge pages where the
/// system allows them, then one MADV_POPULATE_WRITE.
inline void populate_for_write(void* p, std::size_t bytes) {
  advise_huge_pages(p, bytes);
  populate_pages(p, bytes);
}

/// v.resize(n), the pages of any new allocation mapped before they are written.
template <class T>
void resize_prefaulted(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) {
    v.reserve(n);
    populate_for_write(v.data(), n * sizeof(T));
  }
  v.resize(n);
}

/// s.reserve(n) for a text about to be appended to, its new pages mapped in bulk.
inline void reserve_prefaulted(std::string& s, std::size_t n) {
  if (n > s.capacity()) {
    s.reserve(n);
    populate_for_write(s.data(), n);
  }
}

}  // namespace imunoise::detail
