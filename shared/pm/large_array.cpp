// See large_array.h. Two page policies behind one allocator:
//
// PageFill::Now: an anonymous mapping made with MAP_POPULATE maps every page
// (writable, zeroed) in the one call; where that is not honoured (qemu-user, other
// systems) pages fault in at first write, as with operator new. The mapping's
// first page holds its length; the array starts on the next. Freed mappings are
// kept (up to kCachedBytes) and handed out again for arrays of up to their size and
// at least half of it, not cleared (std::vector writes every element it
// constructs). The cap is below what a 1M-triangle build frees at its end, so
// keeping it does not raise the peak of a process that builds and then encodes.
// 4 KiB pages: huge pages made these allocations slower (the kernel compacts
// memory for each one) and the collapse loop no faster.
//
// PageFill::Later: aligned to 2 MiB, the array's whole huge pages advised huge
// (its last, partial one would be resident in full once touched, so the tail
// gets 4 KiB pages). Even with huge pages the kernel clears every page at first
// touch, so a thread at the lowest priority prefaults each new array
// (MADV_POPULATE_WRITE maps pages writable and never changes contents: safe
// beside the decoder's writes, harmless on memory freed meanwhile), moving the
// clearing to an idle core. It starts when the application says so (the kiosk:
// after its first frame, which it must not slow down).
#include "shared/pm/large_array.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>
#if defined(__linux__)
#include <pthread.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace body::pm {
namespace {

constexpr size_t kPage = 4096;
constexpr size_t kHugePage = size_t(2) << 20;
constexpr size_t kCachedBytes = size_t(256) << 20;
constexpr size_t kCachedMappings = 64;

// ---- PageFill::Now: populated mappings, kept for reuse

[[maybe_unused]] bool mapped(size_t bytes, size_t alignment) {
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
    // The list never grows past its reserve: free_large_array (noexcept) must not allocate.
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

void* allocate_mapped(size_t bytes) {
    const size_t length = kPage + (bytes + kPage - 1) / kPage * kPage;  // the length page, then the array
    char* base = cache().take(length);
    if (!base) {
        void* p = ::mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        base = static_cast<char*>(p);
        *reinterpret_cast<size_t*>(base) = length;
    }
    return base + kPage;
}

void free_mapped(void* p) noexcept {
    char* base = static_cast<char*>(p) - kPage;
    const Mapping m{base, *reinterpret_cast<const size_t*>(base)};
    if (!cache().keep(m)) ::munmap(m.base, m.length);
}
#endif

// ---- PageFill::Later: huge pages, prefaulted in the background

#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
// Arrays may be freed during static destruction, after the Prefaulter's; a
// trivially destructible flag says whether it still exists.
std::atomic<bool> g_prefaulter_alive{false};

class Prefaulter {
public:
    static Prefaulter& instance() {
        static Prefaulter p;
        return p;
    }
    void add(void* p, size_t bytes) {
        {
            std::lock_guard guard(mutex_);
            ranges_.emplace_back(static_cast<char*>(p), bytes);
            if (started_ && !thread_.joinable()) thread_ = std::thread([this] { run(); });
        }
        cv_.notify_one();
    }
    // A freed array is no longer prefaulted (nor listed: a program that never
    // starts the thread, bodygen, would keep every range it ever allocated).
    void remove(void* p) {
        std::lock_guard guard(mutex_);
        std::erase_if(ranges_, [p](const std::pair<char*, size_t>& r) { return r.first == p; });
    }
    // The thread itself starts with the first range to prefault: a scene of
    // small files, with no array this large, never runs it.
    void start() {
        std::lock_guard guard(mutex_);
        started_ = true;
        if (!ranges_.empty() && !thread_.joinable()) thread_ = std::thread([this] { run(); });
    }
    ~Prefaulter() {
        g_prefaulter_alive = false;
        {
            std::lock_guard guard(mutex_);
            stop_ = true;
        }
        cv_.notify_one();
        if (thread_.joinable()) thread_.join();
    }

private:
    Prefaulter() { g_prefaulter_alive = true; }
    void run() {
        ::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 19);  // idle cores only
        pthread_setname_np(pthread_self(), "bpm-prefault");
        for (;;) {
            std::pair<char*, size_t> r;
            {
                std::unique_lock guard(mutex_);
                cv_.wait(guard, [&] { return stop_ || !ranges_.empty(); });
                if (stop_) return;
                r = ranges_.front();
                ranges_.pop_front();
            }
            // One huge page at a time: an error (memory freed meanwhile) ends the range.
            for (size_t off = 0; off < r.second; off += kHugePage)
                if (::madvise(r.first + off, std::min(kHugePage, r.second - off), MADV_POPULATE_WRITE) != 0) break;
        }
    }
    std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<std::pair<char*, size_t>> ranges_;
    bool stop_ = false, started_ = false;
    std::thread thread_;
};
#endif

void* allocate_huge(size_t bytes) {
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Advice only: without THP it is ordinary memory.
    const size_t whole = bytes / kHugePage * kHugePage;
    if (whole > 0) ::madvise(p, whole, MADV_HUGEPAGE);
    if (whole < rounded) ::madvise(static_cast<char*>(p) + whole, rounded - whole, MADV_NOHUGEPAGE);
#endif
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    Prefaulter::instance().add(p, std::min(rounded, (bytes + kPage - 1) / kPage * kPage));
#endif
    return p;
}

void free_huge(void* p) noexcept {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    if (p && g_prefaulter_alive) Prefaulter::instance().remove(p);
#endif
    std::free(p);
}

bool huge(size_t bytes) { return bytes >= kLargeArrayBytes; }

// ---- small arrays: operator new, over-aligned as std::allocator does

void* allocate_small(size_t bytes, size_t alignment) {
    if (alignment > __STDCPP_DEFAULT_NEW_ALIGNMENT__) return ::operator new(bytes, std::align_val_t(alignment));
    return ::operator new(bytes);
}

void free_small(void* p, size_t alignment) noexcept {
    if (alignment > __STDCPP_DEFAULT_NEW_ALIGNMENT__)
        ::operator delete(p, std::align_val_t(alignment));
    else
        ::operator delete(p);
}

}  // namespace

void* allocate_large_array(size_t bytes, size_t alignment, PageFill fill) {
    if (fill == PageFill::Later && huge(bytes)) return allocate_huge(bytes);
#if defined(__linux__) && defined(MAP_POPULATE)
    if (fill == PageFill::Now && mapped(bytes, alignment)) return allocate_mapped(bytes);
#endif
    return allocate_small(bytes, alignment);
}

void free_large_array(void* p, size_t bytes, size_t alignment, PageFill fill) noexcept {
    if (!p) return;
    if (fill == PageFill::Later && huge(bytes)) return free_huge(p);
#if defined(__linux__) && defined(MAP_POPULATE)
    if (fill == PageFill::Now && mapped(bytes, alignment)) return free_mapped(p);
#endif
    free_small(p, alignment);
}

void start_background_prefault() {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    Prefaulter::instance().start();
#endif
}

}  // namespace body::pm
