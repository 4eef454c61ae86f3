// See prefaulted_array.h. A large array is an anonymous mapping made with MAP_POPULATE,
// which maps every page (writable, zeroed) in the one call; where it is not honoured
// (qemu-user, other systems) pages fault in as they are first written, as with operator
// new. Its first page holds the mapping's length; the array starts on the next.
//
// Freed mappings are kept (up to kCachedBytes in all) and handed out again for arrays
// of up to their size and at least half of it, as malloc keeps freed memory: building
// structure after structure, or the same one again, then maps nothing new. Kept
// memory is not cleared (std::vector writes every element it constructs). The cap is
// below what a 1M-triangle build frees at its end, so keeping it does not raise the
// peak of a process that builds and then encodes.
//
// Not huge pages: advising the larger arrays MADV_HUGEPAGE before populating them made
// the 1.1M-triangle build's allocations slower, not faster, on the benchmark VM
// (53 MB of corner costs: 95-100 ms against 34-38 ms with 4 KiB pages; the kernel
// compacts memory for each 2 MiB page), and the collapse loop ran no faster.
#include "shared/prefaulted_array.h"

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <vector>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace body {
namespace {

constexpr size_t kPage = 4096;
constexpr size_t kCachedBytes = size_t(256) << 20;
constexpr size_t kCachedMappings = 64;

bool mapped(size_t bytes, size_t alignment) {
#if defined(__linux__) && defined(MAP_POPULATE)
    return bytes >= kPrefaultMinBytes && alignment <= kPage;
#else
    (void)bytes;
    (void)alignment;
    return false;
#endif
}

#if defined(__linux__) && defined(MAP_POPULATE)
struct Mapping {
    char* base;
    size_t length;
};

// Freed mappings kept for reuse (one lock: a few hundred large allocations per build).
class MappingCache {
public:
    // The list never grows past its reserve: free_prefaulted (noexcept) must not allocate.
    MappingCache() { kept_.reserve(kCachedMappings); }
    // The smallest kept mapping of `length` to 2 x `length` bytes, or nullptr.
    char* take(size_t length) {
        std::lock_guard guard(mutex_);
        auto best = kept_.end();
        for (auto it = kept_.begin(); it != kept_.end(); ++it)
            if (it->length >= length && it->length / 2 <= length && (best == kept_.end() || it->length < best->length))
                best = it;
        if (best == kept_.end()) return nullptr;
        char* base = best->base;
        bytes_ -= best->length;
        kept_.erase(best);
        return base;
    }
    // Keeps `m` if the cap allows; false: the caller unmaps it.
    bool keep(const Mapping& m) {
        std::lock_guard guard(mutex_);
        if (bytes_ + m.length > kCachedBytes || kept_.size() >= kCachedMappings) return false;
        kept_.push_back(m);
        bytes_ += m.length;
        return true;
    }

private:
    std::mutex mutex_;
    std::vector<Mapping> kept_;
    size_t bytes_ = 0;
};

// Never destroyed: arrays may be freed during static destruction.
MappingCache& cache() {
    static MappingCache* c = new MappingCache;
    return *c;
}
#endif

}  // namespace

void* allocate_prefaulted(size_t bytes, size_t alignment) {
#if defined(__linux__) && defined(MAP_POPULATE)
    if (mapped(bytes, alignment)) {
        const size_t length = kPage + (bytes + kPage - 1) / kPage * kPage;  // the length page, then the array
        char* base = cache().take(length);
        if (!base) {
            void* p =
                ::mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
            if (p == MAP_FAILED) throw std::bad_alloc();
            base = static_cast<char*>(p);
            *reinterpret_cast<size_t*>(base) = length;
        }
        return base + kPage;
    }
#endif
    return ::operator new(bytes, std::align_val_t(alignment));
}

void free_prefaulted(void* p, size_t bytes, size_t alignment) noexcept {
    if (!p) return;
#if defined(__linux__) && defined(MAP_POPULATE)
    if (mapped(bytes, alignment)) {
        char* base = static_cast<char*>(p) - kPage;
        const Mapping m{base, *reinterpret_cast<const size_t*>(base)};
        if (!cache().keep(m)) ::munmap(m.base, m.length);
        return;
    }
#endif
    ::operator delete(p, std::align_val_t(alignment));
}

}  // namespace body
