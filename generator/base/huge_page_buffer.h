// Large working buffers backed by transparent huge pages. A buffer of hundreds of megabytes
// (a cut-face atlas being baked: 6.7 million texels of 41 bytes for a watermelon wedge) is
// fresh memory that the kernel maps on first touch, one 4 KiB page fault at a time: on a
// virtual machine those faults cost more than the baking itself. Memory asked for with
// madvise(MADV_HUGEPAGE) is mapped 2 MiB at a time, in 512 times fewer faults, where the
// kernel's transparent huge pages are enabled for `madvise` or `always` (Linux' default).
// Contents and results do not depend on it; without huge pages the buffers are plain memory.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace cutaway {

/// Allocations of at least this many bytes are aligned to it and advised to use huge pages.
inline constexpr size_t kHugePageBytes = size_t{2} << 20;

/// Asks the kernel to back `bytes` at `start` (a multiple of kHugePageBytes) with transparent
/// huge pages; does nothing where the kernel cannot or the platform has no such advice.
void advise_huge_pages(void* start, size_t bytes) noexcept;

/// A standard allocator whose blocks of at least kHugePageBytes are aligned to a huge page and
/// advised to use huge pages (advise_huge_pages); smaller blocks come from operator new.
/// Stateless: every instance can free what another allocated.
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() noexcept = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) return static_cast<T*>(::operator new(bytes));
    const size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* p = std::aligned_alloc(kHugePageBytes, rounded);
    if (!p) throw std::bad_alloc();
    advise_huge_pages(p, rounded);
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) < kHugePageBytes) ::operator delete(p);
    else std::free(p);
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

/// A vector whose large storage uses huge pages (HugePageAllocator): for per-texel buffers.
template <typename T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace cutaway
