#pragma once
// Streaming .bpm loading: the file is read in chunks and each chunk decoded as
// it arrives (pm::BpmStream::feed) on the shared decoding threads
// (scene/decode_pool.h), beside the render thread instead of inside its
// frames: on a 2-core board the renderer's vertex work and the decoding then
// overlap, and a frame never waits for a decode budget. The render thread
// draws whatever level has been decoded so far. A loader owns no thread: a
// scene of thousands of files runs on the pool's few, and a file is open only
// while a pool thread reads it.
//
// Sharing: a ProgressiveMesh is not thread-safe, so the stream (and every
// structure in it) may only be touched while holding lock(). A pool thread
// holds it while decoding one slice of a chunk (a few milliseconds at most);
// the render thread holds it while it changes levels and uploads, and
// releases it before drawing (the GL buffers need no lock).
//
// Order: the base meshes of every loader are decoded first (the larger
// `priority` first), then, once release_detail() was called (the kiosk calls
// it after its first frame, so that detail does not compete with the first
// picture), the rest.
//
// On demand (`on_demand`): past the bases the file is decoded only as far as
// want_splits() asks (pm::BpmStream::set_wanted_splits: up to the next batch
// boundary), then the loader pauses, holding no bytes and no scratch, and
// resumes when a want rises. So a scene of thousands of models drawn coarse
// holds coarse levels, not every file's full detail.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "kiosk/scene/decode_pool.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"

namespace body::kiosk {

class StreamLoader final : private DecodeTask {
public:
    // Queues `path` on `pool` for reading and decoding, `chunk_bytes` per read;
    // `priority`: its place among the pool's tasks (larger first).
    explicit StreamLoader(std::string path, size_t chunk_bytes = 64 * 1024, double priority = 0.0,
                          DecodePool& pool = DecodePool::shared(), bool on_demand = false);
    ~StreamLoader() override;  // stops decoding (between two slices) and leaves the pool
    StreamLoader(const StreamLoader&) = delete;
    StreamLoader& operator=(const StreamLoader&) = delete;

    // Blocks until every structure's base mesh is decoded, or decoding is done;
    // decodes them on the calling thread when no pool thread has begun them.
    void wait_for_bases();
    // Lets decoding go past the base meshes. Idempotent.
    void release_detail();
    // Blocks until decoding is done (whole file decoded, or failed). Releases
    // the detail and lifts every want first. For replays: frames that do not depend on timing.
    void wait_until_done();
    // Blocks until decoding is done or paused, or `deadline` passed; true when done or paused.
    bool wait_idle_until(std::chrono::steady_clock::time_point deadline) const;

    // Hold this while touching stream() or its structures. The decoding thread
    // lets a waiting caller in before its next slice (a mutex alone is not fair:
    // it would re-take it at once, slice after slice, and starve the frames).
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
    // Nothing more wanted for now (on demand); want_splits() resumes it.
    bool paused() const { return paused_.load(std::memory_order_relaxed); }
    // Splits of structure `structure` wanted (on demand; BpmStream::set_wanted_splits).
    void want_splits(size_t structure, size_t splits);
    // Why decoding stopped early: a read error, a corrupt section, or a file that
    // ended too soon (BpmStream::finish). Empty when the whole file decoded.
    const std::string& error() const { return error_; }
    size_t bytes_total() const { return total_; }  // the file's size (0 until opened)
    size_t bytes_decoded() const { return decoded_; }
    const std::string& path() const { return path_; }

private:
    DecodeNeed step(std::vector<uint8_t>& buffer) override;
    DecodeNeed finish(std::string error);  // under the lock

    std::string path_;
    size_t chunk_bytes_;
    DecodePool& pool_;
    mutable std::mutex mutex_;
    mutable std::atomic<int> waiting_{0};  // callers blocked in lock()
    // Nothing more will be decoded; set under the lock, and atomic so that
    // wait_idle_until can poll it without the lock.
    std::atomic<bool> done_{false};
    std::atomic<bool> paused_{false};  // likewise: the stream paused (set under the lock)
    mutable std::condition_variable cv_;
    pm::BpmStream stream_;
    bool released_ = false, stop_ = false;
    std::string error_;
    size_t total_ = 0, decoded_ = 0;  // decoded_: also where the next read starts
    bool opened_ = false;
};

}  // namespace body::kiosk
