// A settled level drawn in vertex-cache order (see level_order.h). Phases a
// frame, per model: forget what the geometry left, take a finished job, start
// one once the level settled (a GPU copy of the prefix, mapped, and the cell
// of each vertex); the worker orders one job at a time, in place.
#include "kiosk/render/level_order.h"

#include <algorithm>
#include <utility>

#include "kiosk/render/batch.h"
#include "kiosk/render/buffer_access.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/model.h"
#include "kiosk/render/window_order.h"

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
    job->worker = this;
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

void LevelOrderWorker::release(LevelOrderJob& job) {
    std::unique_lock<std::mutex> lock(mutex_);
    job.dropped = true;  // under the mutex: a queued job is skipped, the one in hand stops
    finished_.wait(lock, [&] { return current_ != &job; });
}

void LevelOrderWorker::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        if (current_) current_->dropped = true;
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
        current_ = job.get();
        lock.unlock();
        // Only this thread touches the job's indices until current_ is reset.
        const bool ordered = order_in_windows(job->indices, job->cells, &job->dropped);
        std::vector<uint16_t>().swap(job->cells);
        lock.lock();
        current_ = nullptr;
        job->ordered = ordered;
        job->done = true;
        if (pending_ > 0) --pending_;
        finished_.notify_all();
    }
}

namespace {

void free_buffer(LevelOrder& o) {
    if (o.ebo) glDeleteBuffers(1, &o.ebo);
    o.ebo = 0;
    o.count = 0;
}

// Unmaps and deletes the job's buffer (bound to GL_COPY_WRITE_BUFFER: no
// vertex array's state); whether its contents were kept while mapped.
bool unmap_pending(LevelOrder& o, bool keep) {
    if (!o.pending) return false;
    glBindBuffer(GL_COPY_WRITE_BUFFER, o.pending);
    const bool kept = glUnmapBuffer(GL_COPY_WRITE_BUFFER) == GL_TRUE;
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    if (!keep || !kept) {
        glDeleteBuffers(1, &o.pending);
        o.pending = 0;
    }
    return kept;
}

// The finished job's buffer drawn from, when it holds the model's level in
// cache order (staged: copied into a new buffer on the GPU first).
void install(Model& m) {
    LevelOrder& o = m.order;
    const std::shared_ptr<LevelOrderJob> job = std::move(o.job);
    const bool current = job->ordered && job->version == m.geometry_version && job->indices.size() == m.index_count;
    if (!unmap_pending(o, current) || !current) return;
    free_buffer(o);
    const GLsizeiptr bytes = static_cast<GLsizeiptr>(job->indices.size() * sizeof(uint32_t));
    if (o.pending_staged) {
        glGenBuffers(1, &o.ebo);
        glBindBuffer(GL_COPY_READ_BUFFER, o.pending);
        glBindBuffer(GL_COPY_WRITE_BUFFER, o.ebo);
        glBufferData(GL_COPY_WRITE_BUFFER, bytes, nullptr, GL_STATIC_DRAW);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, bytes);
        glBindBuffer(GL_COPY_READ_BUFFER, 0);
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
        glDeleteBuffers(1, &o.pending);
        m.transfers->stats.staged_bytes += static_cast<size_t>(bytes);
    } else {
        o.ebo = o.pending;
    }
    o.pending = 0;
    o.count = job->indices.size();
    o.version = job->version;
}

// The cell (window_order.h) of each vertex in the model's box; empty when
// the positions could not be mapped.
std::vector<uint16_t> vertex_cells(const Model& m) {
    const MappedPositions p(m);
    if (!p.ok()) return {};
    std::vector<uint16_t> cells(p.size());
    const Vec3f extent = m.box_max - m.box_min;
    const Vec3f inv(extent.x > 0.0f ? 1.0f / extent.x : 0.0f, extent.y > 0.0f ? 1.0f / extent.y : 0.0f,
                    extent.z > 0.0f ? 1.0f / extent.z : 0.0f);
    for (size_t v = 0; v < cells.size(); ++v) {
        const Vec3f t = (p[v] - m.box_min) * inv;
        cells[v] = order_cell(t.x, t.y, t.z);
    }
    return cells;
}

// A mapped copy of the prefix made on the GPU (in a staging buffer where
// maps that write are staged, see buffer_access.h); 0 when it failed.
GLuint copy_prefix(Model& m, void*& data) {
    const GLsizeiptr bytes = static_cast<GLsizeiptr>(m.index_count * sizeof(uint32_t));
    const bool staged = m.transfers->staged;
    GLuint copy = 0;
    glGenBuffers(1, &copy);
    glBindBuffer(GL_COPY_READ_BUFFER, m.ebo);
    glBindBuffer(GL_COPY_WRITE_BUFFER, copy);
    glBufferData(GL_COPY_WRITE_BUFFER, bytes, nullptr, staged ? GL_STREAM_READ : GL_STATIC_DRAW);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, bytes);
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    data = glMapBufferRange(GL_COPY_WRITE_BUFFER, 0, bytes, GL_MAP_READ_BIT | GL_MAP_WRITE_BIT);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    if (!data) {
        glDeleteBuffers(1, &copy);
        return 0;
    }
    if (staged) {
        m.transfers->stats.staged_bytes += static_cast<size_t>(bytes);
    } else {
        ++m.transfers->stats.in_place_maps;
        ++m.transfers->stats.in_place_writes;
    }
    return copy;
}

// The in-place form (see level_order.h): one slice a frame, the first frame
// after the level settled only counting the buckets.
void refresh_in_place(Model& m, uint64_t serial, double seconds, double settle_seconds, bool& read_back) {
    LevelOrder& o = m.order;
    if (m.geometry_version != o.seen_version) {
        o.seen_version = m.geometry_version;
        o.seen_frame = serial;
        o.seen_seconds = seconds;
    }
    if (o.sliced.done() || read_back) return;
    const size_t bytes = m.index_count * sizeof(uint32_t);
    if (!o.sliced.begun) {
        if (o.tried_version == m.geometry_version || !orders_level(m, settle_seconds)) return;
        if (serial - o.seen_frame < kSettleFrames || seconds - o.seen_seconds < settle_seconds) return;
        read_back = true;
        o.tried_version = m.geometry_version;
        std::vector<uint16_t> cells = vertex_cells(m);
        if (cells.size() != m.vertex_count) return;
        const MappedBuffer<uint32_t> map(m, m.ebo, m.index_count);
        if (map.data().size() == m.index_count) (void)begin_sliced_order(o.sliced, map.data(), std::move(cells));
        return;
    }
    read_back = true;
    MappedRange map(*m.transfers, m.ebo, 0, bytes, GL_MAP_READ_BIT | GL_MAP_WRITE_BIT);
    if (!map.data()) return;  // the next frame tries again
    const bool done = step_sliced_order(
        o.sliced, std::span<uint32_t>(static_cast<uint32_t*>(map.data()), m.index_count), kOrderSliceFaces);
    if (!map.unmap()) o.sliced = SlicedOrder{};  // the store was lost: nothing left to restore
    if (done) trim_heap();  // the windows' scratch (below glibc's grown mmap threshold) back to the system
}

}  // namespace

void refresh_level_order(Model& m, LevelOrderWorker& worker, uint64_t serial, double seconds, double settle_seconds,
                         bool& read_back) {
    LevelOrder& o = m.order;
    if (!o.enabled || settle_seconds < 0.0) return;
    if (orders_in_place(m)) {
        refresh_in_place(m, serial, seconds, settle_seconds, read_back);
        return;
    }
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
    // A lost mapping or positions that cannot be read wait for the next change of level.
    auto job = std::make_shared<LevelOrderJob>();
    job->cells = vertex_cells(m);
    if (job->cells.size() != m.vertex_count) return;
    void* data = nullptr;
    o.pending = copy_prefix(m, data);
    if (!o.pending) return;
    o.pending_staged = m.transfers->staged;
    job->indices = std::span<uint32_t>(static_cast<uint32_t*>(data), m.index_count);
    job->version = m.geometry_version;
    o.job = job;
    worker.submit(std::move(job));
}

bool orders_level(const Model& m, double settle_seconds) {
    return m.order.enabled && settle_seconds >= 0.0 && m.index_count >= 3 * kMinOrderedTriangles;
}

GLuint drawn_element_buffer(const Model& m) { return level_ordered(m) && m.order.ebo ? m.order.ebo : m.ebo; }

bool level_ordered(const Model& m) {
    const LevelOrder& o = m.order;
    if (o.sliced.done()) return o.sliced.perm.size() * 3 == m.index_count;
    return o.ebo && o.version == m.geometry_version && o.count == m.index_count;
}

size_t level_order_bytes(const Model& m) {
    const LevelOrder& o = m.order;
    const SlicedOrder& s = o.sliced;
    const auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    const pm::CacheWindowScratch& w = s.scratch;
    size_t total = o.count * sizeof(uint32_t) + (o.job ? o.job->indices.size_bytes() + bytes(o.job->cells) : 0);
    total += bytes(s.cells) + s.perm.bytes() + bytes(s.start) + bytes(s.next) + bytes(s.faces) + bytes(s.moved) +
             bytes(s.corners) + bytes(s.firsts);
    for (const auto* v : {&w.local_of, &w.local, &w.global, &w.sorted, &w.start, &w.by_first, &w.window})
        total += bytes(*v);
    return total;
}

bool orders_in_place(const Model& m) { return m.vertex_capacity > kMaxBatchedVertices && !m.transfers->staged; }

bool restore_level_prefix(Model& m) {
    SlicedOrder& s = m.order.sliced;
    if (!s.begun) return true;
    const size_t count = s.perm.size() * 3;
    bool ok = count == 0;
    if (!ok) {
        MappedRange map(*m.transfers, m.ebo, 0, count * sizeof(uint32_t), GL_MAP_READ_BIT | GL_MAP_WRITE_BIT);
        if (map.data()) restore_order(std::span<uint32_t>(static_cast<uint32_t*>(map.data()), count), s.perm);
        ok = map.data() && map.unmap();
    }
    s = SlicedOrder{};
    return ok;
}

void free_level_order(Model& m) {
    LevelOrder& o = m.order;
    if (o.job) o.job->worker->release(*o.job);
    o.job.reset();
    (void)unmap_pending(o, false);
    free_buffer(o);
    o.sliced = SlicedOrder{};
}

}  // namespace body::render
