#pragma once
// Streaming model loading: a background thread reads a file in chunks; the
// render thread takes the chunks that have arrived with pump() and hands them
// to the progressive-mesh decoder (pm::BpmStream::feed), a bounded number of
// bytes per frame, so the first frame can draw base meshes while detail is
// still on its way. Decoding stays on the render thread because a
// ProgressiveMesh is not shared across threads (shared/pm/progressive_mesh.h).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "shared/error.h"

namespace body::kiosk {

class StreamLoader {
public:
    using Consumer = std::function<Status(std::span<const uint8_t>)>;

    // Starts reading `path` at once. `chunk_bytes` per read; `max_queued` chunks
    // may wait before the reader pauses (bounded memory).
    explicit StreamLoader(std::string path, size_t chunk_bytes = 256 * 1024, size_t max_queued = 64);
    ~StreamLoader();  // stops and joins the reader
    StreamLoader(const StreamLoader&) = delete;
    StreamLoader& operator=(const StreamLoader&) = delete;

    // Feeds arrived chunks to `consume` until `max_bytes` were fed or none is
    // waiting. Returns the bytes fed, or the first error (from reading or from
    // `consume`); after an error the loader is finished.
    Result<size_t> pump(const Consumer& consume, size_t max_bytes = SIZE_MAX);
    // Everything was read and fed (or it failed).
    bool finished() const;
    size_t bytes_total() const;  // the file's size (0 until opened)
    size_t bytes_fed() const { return fed_; }
    const std::string& path() const { return path_; }
    // Blocks until a chunk is waiting or the reader ended (for tools and tests).
    void wait_for_data() const;

private:
    void run();

    std::string path_;
    size_t chunk_bytes_, max_queued_;
    mutable std::mutex mutex_;
    mutable std::condition_variable cv_;
    std::deque<std::vector<uint8_t>> queue_;
    bool reader_done_ = false, stop_ = false, failed_ = false;
    std::string error_;
    size_t total_ = 0;
    size_t fed_ = 0;
    std::thread thread_;
};

}  // namespace body::kiosk
