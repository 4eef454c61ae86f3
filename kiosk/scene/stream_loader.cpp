// A streamed .bpm read and decoded on the shared decoding threads (contract in stream_loader.h).
#include "kiosk/scene/stream_loader.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "shared/input_file.h"

namespace body::kiosk {

namespace {
// Bytes fed per lock: bounds how long the render thread can wait for the lock
// (one slice completes at most a section or two: ~1-3 ms of decoding).
constexpr size_t kSliceBytes = 16 * 1024;
// Until the bases are in, smaller slices: a slice is decoded whole, and one of
// kSliceBytes would take a small file's detail along with its base (AAL
// regions: ~13 KB each), making the first frame wait for every file's detail.
constexpr size_t kBaseSliceBytes = 2 * 1024;
}  // namespace

StreamLoader::StreamLoader(std::string path, size_t chunk_bytes, double priority, DecodePool& pool, bool on_demand)
    : path_(std::move(path)), chunk_bytes_(chunk_bytes ? chunk_bytes : 1), pool_(pool), stream_(path_) {
    if (on_demand) stream_.set_wanted_splits_all(0);  // the bases, then what want_splits asks
    pool_.add(this, priority);                        // last: a pool thread may step it at once
}

void StreamLoader::want_splits(size_t structure, size_t splits) {
    // Under the lock: the step that paused did so under it, so either it sees the new want or paused_ is set.
    stream_.set_wanted_splits(structure, splits);
    if (paused_.load(std::memory_order_relaxed) && stream_.wants_more()) {
        paused_.store(false, std::memory_order_relaxed);
        pool_.wake(this);
    }
}

StreamLoader::~StreamLoader() {
    {
        std::lock_guard guard(mutex_);
        stop_ = true;
    }
    cv_.notify_all();
    pool_.remove(this);
}
bool StreamLoader::bases_ready() const {
    if (stream_.structure_count_declared() == 0 || stream_.structure_count() < stream_.structure_count_declared())
        return false;
    for (size_t i = 0; i < stream_.structure_count(); ++i)
        if (!stream_.structure(i).base_ready()) return false;
    return true;
}

void StreamLoader::wait_for_bases() {
    // Decodes them here when no pool thread has reached this file yet.
    std::vector<uint8_t> buffer;
    while (!done_.load(std::memory_order_acquire)) {
        {
            std::unique_lock guard = lock();
            if (bases_ready()) return;
        }
        if (!pool_.step_here(this, buffer)) break;
    }
    std::unique_lock guard = lock();
    cv_.wait(guard, [&] { return done_.load(std::memory_order_relaxed) || bases_ready(); });
}

void StreamLoader::release_detail() {
    {
        std::unique_lock guard = lock();
        if (released_) return;
        released_ = true;
    }
    pool_.release(this);
}

void StreamLoader::wait_until_done() {
    release_detail();
    std::unique_lock guard = lock();
    stream_.set_wanted_splits_all(SIZE_MAX);
    if (paused_.load(std::memory_order_relaxed) && stream_.wants_more()) {
        paused_.store(false, std::memory_order_relaxed);
        pool_.wake(this);
    }
    cv_.wait(guard, [&] { return done_.load(std::memory_order_relaxed); });
}

bool StreamLoader::wait_idle_until(std::chrono::steady_clock::time_point deadline) const {
    // Polls instead of waiting on the condition: waking from a timed wait would
    // re-take the mutex past the decoder's fairness check (see lock()).
    while (!done_.load(std::memory_order_acquire) && !paused_.load(std::memory_order_acquire)) {
        if (std::chrono::steady_clock::now() >= deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return true;
}

DecodeNeed StreamLoader::finish(std::string error) {
    error_ = std::move(error);
    done_.store(true, std::memory_order_release);
    cv_.notify_all();
    return DecodeNeed::Done;
}

// Opens the file where the last step stopped and reads on: chunk after chunk
// while the bases are not in, one chunk of detail (so the pool can turn to a
// file of higher priority), nothing past the bases before release_detail().
DecodeNeed StreamLoader::step(std::vector<uint8_t>& chunk) {
    if (!opened_) {
        if (auto regular = check_regular_file(path_); !regular) {  // a FIFO would block fopen
            std::lock_guard guard(mutex_);
            return finish(regular.error().message);
        }
    }
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path_.c_str(), "rb"), &std::fclose);
    std::FILE* f = file.get();
    if (!f) {
        std::lock_guard guard(mutex_);
        return finish(path_ + ": " + std::strerror(errno));
    }
    if (!opened_ && std::fseek(f, 0, SEEK_END) == 0) {
        const long size = std::ftell(f);
        std::lock_guard guard(mutex_);
        total_ = size > 0 ? static_cast<size_t>(size) : 0;
    }
    opened_ = true;
    if (std::fseek(f, static_cast<long>(decoded_), SEEK_SET) != 0) {
        std::lock_guard guard(mutex_);
        return finish(path_ + ": cannot seek to byte " + std::to_string(decoded_));
    }
    chunk.resize(chunk_bytes_);
    for (;;) {
        const size_t n = std::fread(chunk.data(), 1, chunk.size(), f);
        if (n == 0) {
            const bool read_error = std::ferror(f) != 0;
            std::lock_guard guard(mutex_);
            if (read_error) return finish(path_ + ": read error");
            const Status st = stream_.finish();
            return finish(st ? std::string() : st.error().message);
        }
        for (size_t off = 0; off < n;) {
            while (waiting_.load(std::memory_order_relaxed) > 0) std::this_thread::yield();
            std::unique_lock guard(mutex_);
            if (stop_) return finish(std::string());
            const bool had_bases = bases_ready();
            if (had_bases && !released_) return DecodeNeed::Detail;  // detail waits; decoded_ marks the place
            const size_t slice_bytes = std::min(had_bases ? kSliceBytes : kBaseSliceBytes, n - off);
            if (const Status st = stream_.feed(std::span<const uint8_t>(chunk).subspan(off, slice_bytes)); !st)
                return finish(st.error().message);
            decoded_ += slice_bytes;
            off += slice_bytes;
            // Before the pause check: the slice that completes the bases may also reach the wanted level, and a
            // wait_for_bases() caller blocked on cv_ must hear of the bases either way.
            if (!had_bases && bases_ready()) cv_.notify_all();
            if (stream_.paused()) {  // nothing more wanted: the next step reads on from where the stream stopped
                decoded_ = stream_.bytes_consumed();
                paused_.store(true, std::memory_order_release);
                return DecodeNeed::Paused;
            }
        }
        std::lock_guard guard(mutex_);
        if (bases_ready()) return DecodeNeed::Detail;
    }
}

}  // namespace body::kiosk
