#pragma once
// Scratch vectors grown with their fresh pages mapped in one system call. Every first touch of
// a fresh page is a fault, and on a virtual machine a fault is an exit to the hypervisor (about
// 26 us each on the 2-vCPU VM of 2026-12-05, docs/performance.md): a megabyte of scratch then
// costs ~7 ms in 256 faults, against well under one in a single MADV_POPULATE_WRITE.
#include <sys/mman.h>

#include <cstdint>
#include <vector>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older kernels refuse it and the pages fault in as before
#endif

namespace imunoise::detail {

/// v.resize(n), the pages of any new allocation mapped before they are written.
template <class T>
void resize_prefaulted(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) {
    v.reserve(n);
    constexpr std::uintptr_t kPage = 4096;
    const auto first = (reinterpret_cast<std::uintptr_t>(v.data()) + kPage - 1) & ~(kPage - 1);
    const auto last = reinterpret_cast<std::uintptr_t>(v.data() + n) & ~(kPage - 1);
    if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);
  }
  v.resize(n);
}

}  // namespace imunoise::detail
