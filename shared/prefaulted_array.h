#pragma once
// Storage for the large working arrays of batch kernels (the simplifier's per-vertex
// and per-corner state) whose every page is written: the pages are mapped in one
// system call when the array is allocated rather than one page fault at a time as
// it is first written. A first-touch 4 KiB page fault costs 11-15 us on the virtual
// machines the benchmarks run on (measured 2026-11-25; far less on bare metal), and a
// 70k-triangle simplification writes ~5000 fresh pages; mapped ahead, the same pages
// cost 0.9-1.4 us each. The allocator does not clear what it hands out (a reused
// mapping holds old contents); std::vector value-initialises every element it
// constructs, as with std::allocator, so results do not change. Costs nothing extra
// where the whole array is written; capacity reserved and never used is mapped too
// (keep reserve() close to what is used).
//
// Freed large arrays keep their pages for the next ones (up to 256 MB per process,
// as malloc keeps freed memory): building structure after structure maps nothing new.
// Small arrays (under kPrefaultMinBytes) come from operator new. Thread-safe. Throws
// std::bad_alloc like operator new.
//
// Not for arrays whose capacity is reserved ahead of data that may never come (the
// kiosk's streaming reader): those use pm::UninitAllocator (shared/pm/bpm_format.h),
// whose pages are faulted lazily or by a background thread.
#include <cstddef>
#include <new>
#include <vector>

namespace body {

inline constexpr size_t kPrefaultMinBytes = size_t(256) << 10;

// `bytes` of storage aligned to `alignment` (at most 4096 for large arrays); release
// with free_prefaulted(p, bytes, alignment) using the same arguments.
void* allocate_prefaulted(size_t bytes, size_t alignment);
void free_prefaulted(void* p, size_t bytes, size_t alignment) noexcept;

template <class T>
struct PrefaultedAllocator {
    using value_type = T;
    PrefaultedAllocator() = default;
    template <class U>
    PrefaultedAllocator(const PrefaultedAllocator<U>&) noexcept {}
    T* allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_prefaulted(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, size_t n) noexcept { free_prefaulted(p, n * sizeof(T), alignof(T)); }
    template <class U>
    bool operator==(const PrefaultedAllocator<U>&) const noexcept {
        return true;
    }
};

template <class T>
using PrefaultedVector = std::vector<T, PrefaultedAllocator<T>>;

}  // namespace body
