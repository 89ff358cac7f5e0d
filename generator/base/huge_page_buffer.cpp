#include "base/huge_page_buffer.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace cutaway {

void advise_huge_pages(void* start, size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: a kernel without transparent huge pages answers EINVAL, and the memory stays
  // as it was.
  (void)madvise(start, bytes, MADV_HUGEPAGE);
#else
  (void)start;
  (void)bytes;
#endif
}

}  // namespace cutaway
