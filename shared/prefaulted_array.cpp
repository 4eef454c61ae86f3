// See prefaulted_array.h. Large arrays are anonymous mappings: a 2 MiB-aligned
// start and MADV_HUGEPAGE when the array spans at least one whole huge page, then
// MADV_POPULATE_WRITE (Linux 5.14) maps every page in one call. Where either is
// missing (older kernels, qemu-user, other systems) the advice fails harmlessly and
// pages fault in as they are first written, as with operator new.
#include "shared/prefaulted_array.h"

#include <cstdint>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace body {
namespace {

constexpr size_t kPage = 4096;
constexpr size_t kHugePage = size_t(2) << 20;

size_t round_up(size_t bytes, size_t to) { return (bytes + to - 1) / to * to; }

#if defined(__linux__)
bool mapped(size_t bytes, size_t alignment) { return bytes >= kPrefaultMinBytes && alignment <= kPage; }
#endif

}  // namespace

void* allocate_prefaulted(size_t bytes, size_t alignment) {
#if defined(__linux__)
    if (mapped(bytes, alignment)) {
        const size_t length = round_up(bytes, kPage);
        // Huge pages need a 2 MiB-aligned start: map the slack, then give back what lies
        // outside the aligned range.
        const bool huge = length >= kHugePage;
        const size_t mapping = huge ? length + kHugePage : length;
        void* raw = ::mmap(nullptr, mapping, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (raw == MAP_FAILED) throw std::bad_alloc();
        char* p = static_cast<char*>(raw);
        if (huge) {
            char* aligned = reinterpret_cast<char*>(round_up(reinterpret_cast<uintptr_t>(p), kHugePage));
            if (aligned > p) ::munmap(p, size_t(aligned - p));
            if (aligned + length < p + mapping) ::munmap(aligned + length, size_t(p + mapping - (aligned + length)));
            p = aligned;
#if defined(MADV_HUGEPAGE)
            ::madvise(p, length / kHugePage * kHugePage, MADV_HUGEPAGE);
#endif
        }
#if defined(MADV_POPULATE_WRITE)
        ::madvise(p, length, MADV_POPULATE_WRITE);
#endif
        return p;
    }
#endif
    return ::operator new(bytes, std::align_val_t(alignment));
}

void free_prefaulted(void* p, size_t bytes, size_t alignment) noexcept {
    if (!p) return;
#if defined(__linux__)
    if (mapped(bytes, alignment)) {
        ::munmap(p, round_up(bytes, kPage));
        return;
    }
#endif
    ::operator delete(p, std::align_val_t(alignment));
}

}  // namespace body
