#pragma once
// Streaming .bpm loading: one background thread per file reads it in chunks and
// decodes each chunk as it arrives (pm::BpmStream::feed), beside the render
// thread instead of inside its frames: on a 2-core board the renderer's vertex
// work and the decoding then overlap, and a frame never waits for a decode
// budget. The render thread draws whatever level has been decoded so far.
//
// Sharing: a ProgressiveMesh is not thread-safe, so the stream (and every
// structure in it) may only be touched while holding lock(). The thread holds
// it while decoding one slice of a chunk (a few milliseconds at most); the
// render thread holds it while it changes levels and uploads, and releases it
// before drawing (the GL buffers need no lock).
//
// Order: the thread decodes the base meshes at once, then waits until
// release_detail() (the kiosk calls it after its first frame, so that detail
// does not compete with the first picture), then decodes the rest. All loader
// threads share hardware_concurrency - 1 decoding slots, taken per slice, so a
// scene of many files (the AAL brain: 116) leaves a core to the render thread.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"

namespace body::kiosk {

class StreamLoader {
public:
    // Starts reading and decoding `path` at once, `chunk_bytes` per read.
    explicit StreamLoader(std::string path, size_t chunk_bytes = 64 * 1024);
    ~StreamLoader();  // stops the thread (between two slices) and joins it
    StreamLoader(const StreamLoader&) = delete;
    StreamLoader& operator=(const StreamLoader&) = delete;

    // Blocks until every structure's base mesh is decoded, or the thread is done.
    void wait_for_bases() const;
    // Lets decoding go past the base meshes. Idempotent.
    void release_detail();
    // Blocks until the thread is done (whole file decoded, or failed). Releases
    // the detail first. For replays: frames that do not depend on timing.
    void wait_until_done();
    // Blocks until the thread is done or `deadline` passed; true when done.
    bool wait_done_until(std::chrono::steady_clock::time_point deadline) const;

    // Hold this while touching stream() or its structures. The thread lets a
    // waiting caller in before its next slice (a mutex alone is not fair: the
    // thread would re-take it at once, slice after slice, and starve the frames).
    std::unique_lock<std::mutex> lock() const {
        waiting_.fetch_add(1, std::memory_order_relaxed);
        std::unique_lock guard(mutex_);
        waiting_.fetch_sub(1, std::memory_order_relaxed);
        return guard;
    }
    // --- under lock()
    pm::BpmStream& stream() { return stream_; }
    bool bases_ready() const;                                            // every declared structure has its base mesh
    bool done() const { return done_.load(std::memory_order_relaxed); }  // nothing more will be decoded
    // Why decoding stopped early: a read error, a corrupt section, or a file that
    // ended too soon (BpmStream::finish). Empty when the whole file decoded.
    const std::string& error() const { return error_; }
    size_t bytes_total() const { return total_; }  // the file's size (0 until opened)
    size_t bytes_decoded() const { return decoded_; }
    const std::string& path() const { return path_; }

private:
    void run();
    void finish(std::string error);  // under the lock

    std::string path_;
    size_t chunk_bytes_;
    mutable std::mutex mutex_;
    mutable std::atomic<int> waiting_{0};  // callers blocked in lock()
    // Nothing more will be decoded; set under the lock, and atomic so that
    // wait_done_until can poll it without the lock.
    std::atomic<bool> done_{false};
    mutable std::condition_variable cv_;
    pm::BpmStream stream_;
    bool released_ = false, stop_ = false;
    std::string error_;
    size_t total_ = 0, decoded_ = 0;
    std::thread thread_;
};

}  // namespace body::kiosk
