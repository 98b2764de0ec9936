#include "util/large_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace clpt {

void* allocate_on_large_pages(size_t bytes) {
  const size_t rounded = (bytes + kLargePageBytes - 1) / kLargePageBytes * kLargePageBytes;
  if (rounded < bytes) return nullptr;  // wrapped
  void* memory = std::aligned_alloc(kLargePageBytes, rounded == 0 ? kLargePageBytes : rounded);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: harmless where the kernel has no such pages or declines.
  if (memory) (void)madvise(memory, rounded == 0 ? kLargePageBytes : rounded, MADV_HUGEPAGE);
#endif
  return memory;
}

}  // namespace clpt
