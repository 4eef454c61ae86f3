// Huge-page backed storage for the progressive-mesh arrays (see UninitAllocator
// in bpm_format.h): a 1M-triangle structure first-touches ~100 MB while it
// decodes, and with 4 KiB pages the page faults cost as much as the decoding.
#include <cstdlib>
#include <new>

#include "shared/pm/bpm_format.h"
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace body::pm {

void* allocate_large_array(size_t bytes) {
    constexpr size_t kHugePage = size_t(2) << 20;
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    ::madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without THP it is ordinary memory
#endif
    return p;
}

void free_large_array(void* p) { std::free(p); }

}  // namespace body::pm
