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

/// Maps the whole pages inside [p, p + bytes) before they are written: huge pages where the
/// system allows them (transparent huge pages in madvise mode: one fault and one clear per 2 MB
/// instead of 512), then one MADV_POPULATE_WRITE.
inline void populate_for_write(void* p, std::size_t bytes) {
  constexpr std::uintptr_t kPage = 4096;
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const auto first = (begin + kPage - 1) & ~(kPage - 1);
  const auto last = (begin + bytes) & ~(kPage - 1);
  if (last <= first) return;
  const auto huge_first = (first + kHuge - 1) & ~(kHuge - 1);
  const auto huge_last = last & ~(kHuge - 1);
  if (huge_last > huge_first) ::madvise(reinterpret_cast<void*>(huge_first), huge_last - huge_first, MADV_HUGEPAGE);
  ::madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);
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
