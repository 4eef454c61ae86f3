// A reader thread and a bounded chunk queue between it and the render thread.
#include "kiosk/app/stream_loader.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace body::kiosk {

StreamLoader::StreamLoader(std::string path, size_t chunk_bytes, size_t max_queued)
    : path_(std::move(path)), chunk_bytes_(chunk_bytes ? chunk_bytes : 1), max_queued_(max_queued ? max_queued : 1) {
    thread_ = std::thread([this] { run(); });
}

StreamLoader::~StreamLoader() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
}

void StreamLoader::run() {
    std::FILE* f = std::fopen(path_.c_str(), "rb");
    auto finish = [&](std::string error) {
        std::lock_guard lock(mutex_);
        reader_done_ = true;
        if (!error.empty()) {
            failed_ = true;
            error_ = std::move(error);
        }
        cv_.notify_all();
    };
    if (!f) return finish(path_ + ": " + std::strerror(errno));
    if (std::fseek(f, 0, SEEK_END) == 0) {
        const long size = std::ftell(f);
        std::lock_guard lock(mutex_);
        total_ = size > 0 ? static_cast<size_t>(size) : 0;
    }
    std::fseek(f, 0, SEEK_SET);
    for (;;) {
        std::vector<uint8_t> chunk(chunk_bytes_);
        const size_t n = std::fread(chunk.data(), 1, chunk.size(), f);
        if (n == 0) {
            const bool error = std::ferror(f) != 0;
            std::fclose(f);
            return finish(error ? path_ + ": read error" : std::string());
        }
        chunk.resize(n);
        std::unique_lock lock(mutex_);
        cv_.wait(lock, [&] { return stop_ || queue_.size() < max_queued_; });
        if (stop_) {
            std::fclose(f);
            reader_done_ = true;
            return;
        }
        queue_.push_back(std::move(chunk));
        cv_.notify_all();
    }
}

Result<size_t> StreamLoader::pump(const Consumer& consume, size_t max_bytes) {
    size_t fed = 0;
    while (fed < max_bytes) {
        std::vector<uint8_t> chunk;
        {
            std::lock_guard lock(mutex_);
            if (queue_.empty()) {
                if (failed_) return runtime_error(error_);
                break;
            }
            chunk = std::move(queue_.front());
            queue_.pop_front();
        }
        cv_.notify_all();  // room for the reader
        Status st = consume(chunk);
        if (!st) {
            std::lock_guard lock(mutex_);
            failed_ = true;
            error_ = st.error().message;
            queue_.clear();
            stop_ = true;
            cv_.notify_all();
            return st.error();
        }
        fed += chunk.size();
        fed_ += chunk.size();
    }
    return fed;
}

bool StreamLoader::finished() const {
    std::lock_guard lock(mutex_);
    return (reader_done_ && queue_.empty()) || failed_;
}

size_t StreamLoader::bytes_total() const {
    std::lock_guard lock(mutex_);
    return total_;
}

void StreamLoader::wait_for_data() const {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return !queue_.empty() || reader_done_; });
}

}  // namespace body::kiosk
