// Large host arrays on 2 MiB pages where the kernel offers them (Linux transparent huge pages in
// `madvise` mode, Debian's default).
//
// Why: a 640x480 film is about 36 MB of double sums, and a render's launch buffers are as large;
// touching memory the first time costs one page fault per 4 KiB page, and in the virtual machines
// clpt is measured on a fault costs 10-17 us: the film alone took 90 ms of a W1 render before its
// first launch. On 2 MiB pages the same zeroing takes 5 ms (docs/performance.md, "Fixed costs").
#pragma once

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

namespace clpt {

// The large page size asked for (x86-64 and most Linux targets).
constexpr size_t kLargePageBytes = size_t(2) << 20;

// `bytes` (rounded up to whole large pages) aligned to a large page and advised for large pages;
// nullptr when out of memory. Freed with std::free.
void* allocate_on_large_pages(size_t bytes);

// A std::allocator that puts allocations of a large page or more on large pages; smaller ones
// are plain. Stateless: every instance frees what another allocated.
template <class T>
struct LargePageAllocator {
  using value_type = T;
  LargePageAllocator() = default;
  template <class U>
  LargePageAllocator(const LargePageAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    if (n * sizeof(T) < kLargePageBytes) return std::allocator<T>().allocate(n);
    if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    void* memory = allocate_on_large_pages(n * sizeof(T));
    if (!memory) throw std::bad_alloc();
    return static_cast<T*>(memory);
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) < kLargePageBytes) {
      std::allocator<T>().deallocate(p, n);
    } else {
      std::free(p);
    }
  }
  template <class U>
  bool operator==(const LargePageAllocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const LargePageAllocator<U>&) const noexcept {
    return false;
  }
};

// A vector whose storage is on large pages once it is a large page or more.
template <class T>
using LargeVector = std::vector<T, LargePageAllocator<T>>;

}  // namespace clpt
