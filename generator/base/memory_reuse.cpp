#include "base/memory_reuse.h"

#include <cstdlib>  // defines __GLIBC__ with the GNU C library

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace cutaway {

void reuse_freed_memory() {
#if defined(__GLIBC__)
  // Setting either turns off glibc's own adjustment of both.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace cutaway
