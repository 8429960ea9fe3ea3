// raykernel/large_vector.hpp: the storage of the arrays a query reads at random (a BVH's nodes and triangle
// order, a prepared mesh's triangles in leaf order).
//
// A ray reads a handful of 256-byte nodes and leaves scattered over tens of megabytes: on 4 KiB pages most of
// those reads also miss the TLB. An allocation of 2 MiB or more is therefore aligned to 2 MiB and, on Linux,
// marked MADV_HUGEPAGE before it is touched, so that the kernel backs it with transparent huge pages where it
// allows them (the `madvise` and `always` settings of /sys/kernel/mm/transparent_hugepage/enabled); elsewhere,
// or when the kernel declines, it is ordinary memory. Smaller allocations are plain aligned `new`.
// bench/README.md has the measurement (about a fifth of a nearest hit's time on 10^6 triangles).
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace raykernel::detail {

// `bytes` with the given alignment; throws std::bad_alloc.
[[nodiscard]] void* allocate_large(std::size_t bytes, std::size_t alignment);
void deallocate_large(void* p, std::size_t bytes, std::size_t alignment) noexcept;

template <class T>
struct LargeAllocator {
  using value_type = T;
  LargeAllocator() noexcept = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor): allocator rebinding
  [[nodiscard]] T* allocate(std::size_t n) { return static_cast<T*>(allocate_large(n * sizeof(T), alignof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { deallocate_large(p, n * sizeof(T), alignof(T)); }
  template <class U>
  bool operator==(const LargeAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;

}  // namespace raykernel::detail
