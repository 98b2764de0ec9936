#include "util/large_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace clpt {

void* allocate_on_large_pages(size_t bytes) {
  const size_t pages = bytes == 0 ? 1 : (bytes - 1) / kLargePageBytes + 1;
  if (pages > size_t(-1) / kLargePageBytes) return nullptr;
  const size_t size = pages * kLargePageBytes;
  void* memory = std::aligned_alloc(kLargePageBytes, size);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: harmless where the kernel has no such pages or declines.
  if (memory) (void)madvise(memory, size, MADV_HUGEPAGE);
#endif
  return memory;
}

}  // namespace clpt
