// A settled level drawn in vertex-cache order (see level_order.h). Phases a
// frame, per model: forget what the geometry left, take a finished job, start
// one once the level settled; the worker orders one job at a time.
#include "kiosk/render/level_order.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <utility>

#include "kiosk/render/buffer_access.h"
#include "kiosk/render/model.h"

namespace body::render {

void LevelOrderWorker::start() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (thread_.joinable()) return;
    stopping_ = false;
    thread_ = std::thread([this] { run(); });
}

void LevelOrderWorker::submit(std::shared_ptr<LevelOrderJob> job) {
    start();
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(job));
    ++pending_;
    wake_.notify_one();
}

bool LevelOrderWorker::idle() {
    std::lock_guard<std::mutex> lock(mutex_);
    return pending_ == 0;
}

bool LevelOrderWorker::done(const LevelOrderJob& job) {
    std::lock_guard<std::mutex> lock(mutex_);
    return job.done;
}

void LevelOrderWorker::wait(const LevelOrderJob& job) {
    std::unique_lock<std::mutex> lock(mutex_);
    finished_.wait(lock, [&] { return job.done || !thread_.joinable() || stopping_; });
}

void LevelOrderWorker::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        queue_.clear();
        pending_ = 0;
        wake_.notify_one();
    }
    if (thread_.joinable()) thread_.join();
    finished_.notify_all();
}

void LevelOrderWorker::run() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        std::shared_ptr<LevelOrderJob> job = std::move(queue_.front());
        queue_.pop_front();
        if (job->dropped) {
            if (pending_ > 0) --pending_;  // 0 after a stop
            continue;
        }
        lock.unlock();
        // Only this thread touches the job's arrays until `done` is set.
        std::vector<uint32_t> ordered = order_level(job->indices, job->vertex_count);
        std::vector<uint32_t>().swap(job->indices);
        lock.lock();
        job->indices = std::move(ordered);
        job->done = true;
        if (pending_ > 0) --pending_;
        finished_.notify_all();
    }
}

std::vector<uint32_t> order_level(std::span<const uint32_t> indices, size_t vertex_count) {
    if (indices.size() % 3 != 0) return {};
    if (std::any_of(indices.begin(), indices.end(), [&](uint32_t i) { return i >= vertex_count; })) return {};
    std::vector<uint32_t> out(indices.size());
    meshopt_optimizeVertexCache(out.data(), indices.data(), indices.size(), vertex_count);
    return out;
}

namespace {

void free_buffer(LevelOrder& o) {
    if (o.ebo) glDeleteBuffers(1, &o.ebo);
    o.ebo = 0;
    o.count = 0;
}

// The finished job's triangles in a new element buffer, when they are still
// the model's level (bound to GL_COPY_WRITE_BUFFER: no vertex array's state).
void install(Model& m) {
    LevelOrder& o = m.order;
    const std::shared_ptr<LevelOrderJob> job = std::move(o.job);
    if (job->version != m.geometry_version || job->indices.size() != m.index_count) return;
    free_buffer(o);
    glGenBuffers(1, &o.ebo);
    glBindBuffer(GL_COPY_WRITE_BUFFER, o.ebo);
    glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(job->indices.size() * sizeof(uint32_t)),
                 job->indices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    o.count = job->indices.size();
    o.version = job->version;
}

}  // namespace

void refresh_level_order(Model& m, LevelOrderWorker& worker, uint64_t serial, double seconds, double settle_seconds,
                         bool& read_back) {
    LevelOrder& o = m.order;
    if (!o.enabled || settle_seconds < 0.0) return;
    if (m.geometry_version != o.seen_version) {
        o.seen_version = m.geometry_version;
        o.seen_frame = serial;
        o.seen_seconds = seconds;
        if (o.ebo && o.version != m.geometry_version) free_buffer(o);  // keep only the current level's
        if (o.job && o.job->version != m.geometry_version) free_level_order(m);
    }
    if (o.job) {
        if (worker.done(*o.job)) install(m);
        return;
    }
    if (o.ebo || o.tried_version == m.geometry_version || !orders_level(m, settle_seconds)) return;
    if (serial - o.seen_frame < kSettleFrames || seconds - o.seen_seconds < settle_seconds) return;
    if (read_back || !worker.idle()) return;
    read_back = true;
    o.tried_version = m.geometry_version;
    // The prefix read back once (in place where the GPU shares memory; a lost
    // mapping waits for the next change of level).
    const MappedBuffer<uint32_t> map(m, m.ebo, m.index_count);
    if (map.data().size() != m.index_count) return;
    auto job = std::make_shared<LevelOrderJob>();
    job->indices.assign(map.data().begin(), map.data().end());
    job->vertex_count = m.vertex_count;
    job->version = m.geometry_version;
    o.job = job;
    worker.submit(std::move(job));
}

bool orders_level(const Model& m, double settle_seconds) {
    return m.order.enabled && settle_seconds >= 0.0 && m.index_count >= 3 * kMinOrderedTriangles;
}

GLuint drawn_element_buffer(const Model& m) { return level_ordered(m) ? m.order.ebo : m.ebo; }

bool level_ordered(const Model& m) {
    const LevelOrder& o = m.order;
    return o.ebo && o.version == m.geometry_version && o.count == m.index_count;
}

void free_level_order(Model& m) {
    LevelOrder& o = m.order;
    free_buffer(o);
    if (o.job) o.job->dropped = true;  // the worker skips it if it has not begun
    o.job.reset();
}

}  // namespace body::render
