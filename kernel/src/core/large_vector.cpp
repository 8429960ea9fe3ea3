// allocate_large / deallocate_large (<raykernel/large_vector.hpp>): 2 MiB-aligned storage marked for
// transparent huge pages from 2 MiB on, aligned `new` below.
#include <raykernel/large_vector.hpp>

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace raykernel::detail {
namespace {

constexpr std::size_t huge_page = std::size_t{2} << 20;

std::size_t rounded_to_huge_pages(std::size_t bytes) { return (bytes + huge_page - 1) / huge_page * huge_page; }

}  // namespace

void* allocate_large(std::size_t bytes, std::size_t alignment) {
  if (bytes < huge_page) return ::operator new(bytes, std::align_val_t{alignment});
  if (bytes > std::size_t(-1) - huge_page) throw std::bad_alloc();
  const std::size_t size = rounded_to_huge_pages(bytes);
  void* p = std::aligned_alloc(huge_page, size);
  if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  (void)madvise(p, size, MADV_HUGEPAGE);  // advice only: refused, the memory is ordinary pages
#endif
  return p;
}

void deallocate_large(void* p, std::size_t bytes, std::size_t alignment) noexcept {
  if (p == nullptr) return;
  if (bytes < huge_page) {
    ::operator delete(p, std::align_val_t{alignment});
    return;
  }
  std::free(p);
}

}  // namespace raykernel::detail
