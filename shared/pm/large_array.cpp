// Huge-page backed storage for the progressive-mesh arrays (see UninitAllocator
// in bpm_format.h): a 1M-triangle structure first-touches ~120 MB while it
// decodes, and with 4 KiB pages the page faults cost as much as the decoding.
//
// Even with huge pages the kernel must clear every page the decoder touches
// first (a fifth of a 1M-triangle decode). So a background thread at the lowest
// priority prefaults each new array (MADV_POPULATE_WRITE: maps the pages
// writable, never changes contents, so it is safe beside the decoder's writes
// and harmless on memory freed meanwhile): the clearing moves to a core the
// decoder does not use, when one is idle. It starts when the application says
// so (the kiosk: after its first frame, which it must not slow down).
//
// Only an array's whole huge pages are advised huge: its last, partial 2 MiB
// would otherwise be resident in full once touched (a 2.2 MB array cost 4 MiB;
// ten such arrays wasted 10 MiB in a 1M-triangle structure). The tail gets 4 KiB
// pages and only its used part is prefaulted.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <new>
#include <thread>
#include <utility>

#include "shared/pm/bpm_format.h"
#if defined(__linux__)
#include <pthread.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace body::pm {

namespace {

constexpr size_t kHugePage = size_t(2) << 20;

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
        }
        cv_.notify_one();
    }
    // A freed array is no longer prefaulted (nor listed: a program that never
    // starts the thread, bodygen, would keep every range it ever allocated).
    void remove(void* p) {
        std::lock_guard guard(mutex_);
        std::erase_if(ranges_, [p](const std::pair<char*, size_t>& r) { return r.first == p; });
    }
    void start() {
        std::lock_guard guard(mutex_);
        if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
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
    bool stop_ = false;
    std::thread thread_;
};
#endif

}  // namespace

void* allocate_large_array(size_t bytes) {
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
    constexpr size_t kPage = 4096;
    Prefaulter::instance().add(p, std::min(rounded, (bytes + kPage - 1) / kPage * kPage));
#endif
    return p;
}

void free_large_array(void* p) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    if (p && g_prefaulter_alive) Prefaulter::instance().remove(p);
#endif
    std::free(p);
}

void start_background_prefault() {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    Prefaulter::instance().start();
#endif
}

}  // namespace body::pm
