#pragma once
// Mapping a model's GL buffers for the CPU (BufferAccess): GLES 3.0 can only
// map them. A map that writes is in place or staged through a temporary
// buffer; reads map in place either way.
#include <GLES3/gl3.h>

#include <cstddef>
#include <cstring>
#include <span>

#include "kiosk/render/model.h"

namespace body::render {

// How models' buffers are written (BufferAccess), and what the maps moved
// (the renderer's state holds one; each model points to it).
struct Transfers {
    bool staged = false;  // BufferAccess::Staged, as init() resolved it
    TransferStats stats;
};

// A byte range of a model's GL buffer mapped for one scope, as
// Transfers::staged says (see BufferAccess): the buffer itself, or, for a map
// that writes, a temporary buffer that the range is copied into on the GPU
// first (unless the map invalidates it) and out of at the end, deleted after
// (reads map in place either way). Bound to GL_COPY_READ_BUFFER /
// GL_COPY_WRITE_BUFFER only, which are no VAO's state, and unbound after each
// step.
class MappedRange {
public:
    MappedRange(Transfers& transfers, GLuint buffer, size_t offset, size_t bytes, GLbitfield access);
    ~MappedRange() { (void)unmap(); }
    MappedRange(const MappedRange&) = delete;
    MappedRange& operator=(const MappedRange&) = delete;

    // Null when the mapping failed (or the range is empty).
    void* data() const { return data_; }
    // Ends the mapping (staged and written: copies the range back). False when
    // the driver lost the store while mapped (GL_FALSE from glUnmapBuffer, e.g.
    // a display mode change): the range's contents are undefined.
    bool unmap();

private:
    void release_staging();
    Transfers& transfers_;
    GLuint buffer_, staging_ = 0;
    size_t offset_, bytes_;
    void* data_ = nullptr;
};

// A model's GL buffer mapped for reading for one scope, from its start (a
// MappedRange: in place, where llvmpipe hands out its storage and nothing is
// copied).
template <typename T>
class MappedBuffer {
public:
    MappedBuffer(const Model& m, GLuint buffer, size_t count)
        : range_(*m.transfers, buffer, 0, count * sizeof(T), GL_MAP_READ_BIT) {
        if (range_.data()) data_ = std::span<const T>(static_cast<const T*>(range_.data()), count);
    }
    std::span<const T> data() const { return data_; }

private:
    MappedRange range_;
    std::span<const T> data_;
};

// A model's GL positions for reading, in either format (a MappedBuffer).
class MappedPositions {
public:
    explicit MappedPositions(const Model& m)
        : m_(m), map_(m, m.vbo_position, m.vertex_count * m.position_stride() / 2) {}
    bool ok() const { return map_.data().size() * 2 == m_.vertex_count * m_.position_stride(); }
    size_t size() const { return m_.vertex_count; }
    Vec3f operator[](size_t v) const {
        const uint16_t* q = map_.data().data() + v * (m_.position_stride() / 2);
        if (!m_.quantized) {
            Vec3f p;
            std::memcpy(&p, q, sizeof(p));
            return p;
        }
        return m_.pos_origin + m_.pos_scale * Vec3f(q[0], q[1], q[2]);
    }
    const uint16_t* codes() const { return map_.data().data(); }  // quantized: 3 per vertex

private:
    const Model& m_;
    MappedBuffer<uint16_t> map_;
};

}  // namespace body::render
