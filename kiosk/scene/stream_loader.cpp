// A reader-and-decoder thread per streamed .bpm (contract in stream_loader.h).
#include "kiosk/scene/stream_loader.h"

#include <pthread.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <semaphore>
#include <span>
#include <thread>
#include <vector>

#include "shared/input_file.h"

namespace body::kiosk {

namespace {
// Bytes fed per lock: bounds how long the render thread can wait for the lock
// (one slice completes at most a section or two: ~1-3 ms of decoding).
constexpr size_t kSliceBytes = 16 * 1024;

// Decoding slots shared by every loader: one core fewer than the machine has, so
// that a scene of many files (the AAL brain: 116) does not put all its threads
// against the render thread while it compiles shaders and draws the first frame.
std::counting_semaphore<1024>& decode_slots() {
    static std::counting_semaphore<1024> slots(
        std::ptrdiff_t(std::clamp(std::thread::hardware_concurrency(), 2u, 1025u) - 1));
    return slots;
}

struct DecodeSlot {
    DecodeSlot() { decode_slots().acquire(); }
    ~DecodeSlot() { decode_slots().release(); }
    DecodeSlot(const DecodeSlot&) = delete;
    DecodeSlot& operator=(const DecodeSlot&) = delete;
};
}  // namespace

StreamLoader::StreamLoader(std::string path, size_t chunk_bytes)
    : path_(std::move(path)), chunk_bytes_(chunk_bytes ? chunk_bytes : 1), stream_(path_) {
    thread_ = std::thread([this] { run(); });
}

StreamLoader::~StreamLoader() {
    {
        std::lock_guard guard(mutex_);
        stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
}

bool StreamLoader::bases_ready() const {
    if (stream_.structure_count_declared() == 0 || stream_.structure_count() < stream_.structure_count_declared())
        return false;
    for (size_t i = 0; i < stream_.structure_count(); ++i)
        if (!stream_.structure(i).base_ready()) return false;
    return true;
}

void StreamLoader::wait_for_bases() const {
    std::unique_lock guard = lock();
    cv_.wait(guard, [&] { return done_.load(std::memory_order_relaxed) || bases_ready(); });
}

void StreamLoader::release_detail() {
    {
        std::unique_lock guard = lock();
        released_ = true;
    }
    cv_.notify_all();
}

void StreamLoader::wait_until_done() {
    release_detail();
    std::unique_lock guard = lock();
    cv_.wait(guard, [&] { return done_.load(std::memory_order_relaxed); });
}

bool StreamLoader::wait_done_until(std::chrono::steady_clock::time_point deadline) const {
    // Polls instead of waiting on the condition: waking from a timed wait would
    // re-take the mutex past the thread's fairness check (see lock()).
    while (!done_.load(std::memory_order_acquire)) {
        if (std::chrono::steady_clock::now() >= deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return true;
}

void StreamLoader::finish(std::string error) {
    error_ = std::move(error);
    done_.store(true, std::memory_order_release);
    cv_.notify_all();
}

void StreamLoader::run() {
    pthread_setname_np(pthread_self(), "bodyview-load");       // for top and perf
    if (auto regular = check_regular_file(path_); !regular) {  // a FIFO would block fopen
        std::lock_guard guard(mutex_);
        return finish(regular.error().message);
    }
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path_.c_str(), "rb"), &std::fclose);
    std::FILE* f = file.get();
    if (!f) {
        std::lock_guard guard(mutex_);
        return finish(path_ + ": " + std::strerror(errno));
    }
    if (std::fseek(f, 0, SEEK_END) == 0) {
        const long size = std::ftell(f);
        std::lock_guard guard(mutex_);
        total_ = size > 0 ? static_cast<size_t>(size) : 0;
    }
    std::fseek(f, 0, SEEK_SET);
    std::vector<uint8_t> chunk(chunk_bytes_);
    for (;;) {
        const size_t n = std::fread(chunk.data(), 1, chunk.size(), f);
        if (n == 0) {
            const bool read_error = std::ferror(f) != 0;
            std::lock_guard guard(mutex_);
            if (read_error) return finish(path_ + ": read error");
            const Status st = stream_.finish();
            return finish(st ? std::string() : st.error().message);
        }
        for (size_t off = 0; off < n; off += kSliceBytes) {
            {
                // Past the bases, detail waits for the first frame.
                std::unique_lock guard(mutex_);
                cv_.wait(guard, [&] { return stop_ || released_ || !bases_ready(); });
            }
            while (waiting_.load(std::memory_order_relaxed) > 0) std::this_thread::yield();
            DecodeSlot slot;
            std::unique_lock guard(mutex_);
            if (stop_) return finish(std::string());
            const auto slice = std::span<const uint8_t>(chunk).subspan(off, std::min(kSliceBytes, n - off));
            const bool had_bases = bases_ready();
            if (const Status st = stream_.feed(slice); !st) return finish(st.error().message);
            decoded_ += slice.size();
            if (!had_bases && bases_ready()) cv_.notify_all();
        }
    }
}

}  // namespace body::kiosk
