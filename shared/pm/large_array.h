#pragma once
// Storage for the large arrays of progressive meshes, in the builder (the
// simplifier's per-vertex and per-corner state, the build it returns) and in the
// reader (a structure's arrays): one allocator, LargeArrayAllocator, with one of
// two page policies chosen by what the array's pages will see.
//
//   PageFill::Now    every page will be written (batch kernels): the pages are
//                    mapped in the allocation's one system call instead of one
//                    page fault each at first write. Freed arrays keep their pages
//                    for the next ones (up to 256 MB per process, as malloc keeps
//                    freed memory). Elements are value-initialised, as with
//                    std::allocator. Arrays from kPrefaultMinBytes.
//   PageFill::Later  capacity reserved ahead of data that may never come (the
//                    streaming reader): transparent huge pages, faulted on first
//                    touch or ahead by a low-priority thread once
//                    start_background_prefault() was called. Elements are
//                    default-initialised (a trivial one is indeterminate until
//                    written). Arrays from kLargeArrayBytes.
//
// Smaller arrays come from operator new. Thread-safe; throws std::bad_alloc like
// operator new. Results never depend on the policy, only page faults do.
#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace body::pm {

enum class PageFill { Now, Later };
inline constexpr size_t kPrefaultMinBytes = size_t(256) << 10;  // PageFill::Now: mapped from here
inline constexpr size_t kLargeArrayBytes = size_t(2) << 20;     // PageFill::Later: huge pages from here

// `bytes` of storage aligned to `alignment` (PageFill::Now: at most 4096 for mapped
// arrays); release with free_large_array and the same arguments.
void* allocate_large_array(size_t bytes, size_t alignment, PageFill fill);
void free_large_array(void* p, size_t bytes, size_t alignment, PageFill fill) noexcept;

// From now on a low-priority thread prefaults the PageFill::Later arrays allocated
// before and after the call; it starts with the first such array (none: no thread).
// Without the call, nothing runs (bodygen never calls it).
void start_background_prefault();

// A cache hint, no effect on results: the split replay (reader and writer) and
// the simplifier's collapse loop are bound by memory latency, and their
// scattered lines are independent, so they are requested ahead of use.
inline void prefetch(const void* p) {
#if defined(__GNUC__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
}
// How many entries ahead a loop over a large batch in a scattered order
// (faces by sorted order, vertices by a face's corner) requests the lines it
// will read: the batched decode's gathers (draw_order.cpp, order_batch).
inline constexpr size_t kGatherAhead = 16;

template <class T, PageFill Fill>
struct LargeArrayAllocator {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = LargeArrayAllocator<U, Fill>;
    };
    LargeArrayAllocator() = default;
    template <class U>
    LargeArrayAllocator(const LargeArrayAllocator<U, Fill>&) noexcept {}
    T* allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_large_array(n * sizeof(T), alignof(T), Fill));
    }
    void deallocate(T* p, size_t n) noexcept { free_large_array(p, n * sizeof(T), alignof(T), Fill); }
    // PageFill::Later: a value-less construct() default-initialises, so resize()
    // leaves trivial elements unwritten (no page faults for capacity not used yet).
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        if constexpr (Fill == PageFill::Later && sizeof...(Args) == 0)
            ::new (static_cast<void*>(p)) U;
        else
            ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    template <class U>
    bool operator==(const LargeArrayAllocator<U, Fill>&) const noexcept {
        return true;
    }
};

// Arrays whose every element is written (PageFill::Now).
template <class T>
using PrefaultedVector = std::vector<T, LargeArrayAllocator<T, PageFill::Now>>;
// Arrays filled as data arrives (PageFill::Later): elements past what was
// written are indeterminate, write before reading.
template <class T>
using UninitVector = std::vector<T, LargeArrayAllocator<T, PageFill::Later>>;

}  // namespace body::pm
