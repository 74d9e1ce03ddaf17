// glibc freezes its mmap threshold at 128 KiB once any of its thresholds is
// set (mallopt(3): setting one disables the dynamic adjustment). A Dask
// worker is started with MALLOC_TRIM_THRESHOLD_=65536 to hand freed memory
// back to the system; the side effect is that every block above 128 KiB is
// mapped and unmapped at each allocation, and the calibration allocates
// matrices of 0.2 to 0.7 MB at each iteration: about 1000 fresh mappings a
// robot, each faulted in page by page. With the mmap threshold raised the
// same blocks come from the heap, and trimming its top to 64 KiB faults them
// in again; a top pad as large keeps them. Freed memory beyond that still
// goes back to the system, as the worker asked.
#include "python/allocator.hpp"

#include <cstdlib>

#include <malloc.h>

namespace gpm::python {

bool keep_large_blocks_on_the_heap() {
#ifdef M_MMAP_THRESHOLD
  if (std::getenv("MALLOC_TRIM_THRESHOLD_") == nullptr || std::getenv("MALLOC_MMAP_THRESHOLD_") != nullptr) return false;
  constexpr int kGlibcDynamicMaximum = 32 * 1024 * 1024;  // DEFAULT_MMAP_THRESHOLD_MAX on 64-bit
  return mallopt(M_MMAP_THRESHOLD, kGlibcDynamicMaximum) == 1 && mallopt(M_TOP_PAD, kGlibcDynamicMaximum) == 1;
#else
  return false;
#endif
}

}  // namespace gpm::python
