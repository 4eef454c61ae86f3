// See prefaulted_array.h. Large arrays are anonymous mappings made with MAP_POPULATE,
// which maps every page (writable, zeroed) in the one call. Where it is not honoured
// (qemu-user, other systems) pages fault in as they are first written, as with
// operator new.
//
// Not huge pages: advising the larger arrays MADV_HUGEPAGE before populating them made
// the 1.1M-triangle build's allocations slower, not faster, on the benchmark VM
// (53 MB of corner costs: 95-100 ms against 34-38 ms with 4 KiB pages; the kernel
// compacts memory to find each 2 MiB page), and the collapse loop ran no faster.
#include "shared/prefaulted_array.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace body {
namespace {

constexpr size_t kPage = 4096;

size_t page_rounded(size_t bytes) { return (bytes + kPage - 1) / kPage * kPage; }

bool mapped(size_t bytes, size_t alignment) {
#if defined(__linux__) && defined(MAP_POPULATE)
    return bytes >= kPrefaultMinBytes && alignment <= kPage;
#else
    (void)bytes;
    (void)alignment;
    return false;
#endif
}

}  // namespace

void* allocate_prefaulted(size_t bytes, size_t alignment) {
#if defined(__linux__) && defined(MAP_POPULATE)
    if (mapped(bytes, alignment)) {
        void* p = ::mmap(nullptr, page_rounded(bytes), PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        return p;
    }
#endif
    return ::operator new(bytes, std::align_val_t(alignment));
}

void free_prefaulted(void* p, size_t bytes, size_t alignment) noexcept {
    if (!p) return;
#if defined(__linux__) && defined(MAP_POPULATE)
    if (mapped(bytes, alignment)) {
        ::munmap(p, page_rounded(bytes));
        return;
    }
#endif
    ::operator delete(p, std::align_val_t(alignment));
}

}  // namespace body
