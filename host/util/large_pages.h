// Large host arrays on 2 MiB pages where the kernel offers them (Linux transparent huge pages in
// `madvise` mode, Debian's default).
//
// Why: a 640x480 film is about 36 MB of double sums, and touching it the first time costs one
// page fault per 4 KiB page. In the virtual machines clpt is measured on a fault costs about
// 10 us, so the film alone took 90 ms of a W1 render before its first launch
// (docs/performance.md, "Fixed costs"); on 2 MiB pages the same zeroing takes 5 ms.
#pragma once

#include <cstddef>
#include <vector>

namespace clpt {

// The large page size asked for (x86-64 and most Linux targets).
constexpr size_t kLargePageBytes = size_t(2) << 20;

// Asks the kernel to back the whole 2 MiB pages inside [data, data + bytes) with huge pages.
// Advice only: a no-op where the kernel has no such pages, and harmless when it declines.
void advise_large_pages(void* data, size_t bytes);

// A vector of n value-initialised (zero) elements whose storage was advised before it was first
// touched. The same contents as std::vector<T>(n).
template <class T>
std::vector<T> zeroed_large_vector(size_t n) {
  std::vector<T> v;
  v.reserve(n);
  advise_large_pages(v.data(), n * sizeof(T));
  v.resize(n);
  return v;
}

}  // namespace clpt
