// The process's allocator as gpm's numerics need it (python/allocator.cpp).
#pragma once

namespace gpm::python {

// Where the environment sets glibc's trim threshold (MALLOC_TRIM_THRESHOLD_,
// as a Dask nanny does for its workers) and leaves its mmap threshold alone,
// sets the mmap threshold to glibc's own dynamic maximum (32 MiB) and keeps
// that much free at the heap's top when trimming; otherwise does nothing.
// Returns whether it set them.
bool keep_large_blocks_on_the_heap();

}  // namespace gpm::python
