// A model's GL buffers grown as its data arrives (contract in buffer_growth.h).
#include "kiosk/render/buffer_growth.h"

#include <algorithm>

#include "kiosk/render/programs.h"

namespace body::render {
namespace {

// A new buffer of `new_bytes` holding the first `old_bytes` of `old`, which is deleted.
GLuint regrow(GLuint old, size_t old_bytes, size_t new_bytes) {
    GLuint grown = 0;
    glGenBuffers(1, &grown);
    glBindBuffer(GL_COPY_WRITE_BUFFER, grown);
    glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(new_bytes), nullptr, GL_DYNAMIC_DRAW);
    if (old && old_bytes) {
        glBindBuffer(GL_COPY_READ_BUFFER, old);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, static_cast<GLsizeiptr>(old_bytes));
        glBindBuffer(GL_COPY_READ_BUFFER, 0);
    }
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    if (old) glDeleteBuffers(1, &old);
    return grown;
}

size_t grown_size(size_t allocated, size_t count, size_t capacity) {
    return std::min(capacity, std::max(count, allocated * 2));
}

}  // namespace

void position_pointer(const Model& m, GLuint location) {
    if (m.quantized)
        glVertexAttribPointer(location, 3, GL_UNSIGNED_SHORT, GL_FALSE, 6, nullptr);
    else
        glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
}

void normal_pointer(const Model& m) {
    if (m.normal_codes) {
        glVertexAttribPointer(kNormalCode, 2, GL_UNSIGNED_BYTE, GL_FALSE, 2, nullptr);
        glEnableVertexAttribArray(kNormalCode);
    } else {
        glVertexAttribPointer(kNormal, 4, GL_INT_2_10_10_10_REV, GL_TRUE, 4, nullptr);
        glEnableVertexAttribArray(kNormal);
    }
}

void reserve_vertices(Model& m, size_t count) {
    if (count <= m.vertex_allocated || m.vertex_allocated >= m.vertex_capacity) return;
    const size_t n = grown_size(m.vertex_allocated, count, m.vertex_capacity);
    glBindVertexArray(m.vao);
    const size_t ps = m.position_stride(), ns = m.normal_stride();
    m.vbo_position = regrow(m.vbo_position, m.vertex_allocated * ps, n * ps);
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_position);
    position_pointer(m, kPosition);
    if (m.vbo_morph) {
        m.vbo_morph = regrow(m.vbo_morph, m.vertex_allocated * ps, n * ps);
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
        position_pointer(m, kMorph);
    }
    m.vbo_normal = regrow(m.vbo_normal, m.vertex_allocated * ns, n * ns);
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_normal);
    normal_pointer(m);
    glBindVertexArray(0);
    m.vertex_allocated = n;
}

void reserve_indices(Model& m, size_t count) {
    if (count <= m.index_allocated || m.index_allocated >= m.index_capacity) return;
    const size_t n = grown_size(m.index_allocated, count, m.index_capacity);
    glBindVertexArray(m.vao);
    m.ebo = regrow(m.ebo, m.index_allocated * 4, n * 4);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
    glBindVertexArray(0);
    m.index_allocated = n;
}

}  // namespace body::render
