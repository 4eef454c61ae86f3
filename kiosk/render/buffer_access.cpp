// Mapped ranges of model buffers, in place or staged (see buffer_access.h).
#include "kiosk/render/buffer_access.h"

namespace body::render {

MappedRange::MappedRange(Transfers& transfers, GLuint buffer, size_t offset, size_t bytes, GLbitfield access)
    : transfers_(transfers), buffer_(buffer), offset_(offset), bytes_(bytes) {
    if (bytes == 0) return;
    GLuint mapped = buffer;
    size_t at = offset;
    if (transfers.staged && (access & GL_MAP_WRITE_BIT)) {
        const bool reads = (access & GL_MAP_READ_BIT) != 0;
        const bool keeps = reads || (access & (GL_MAP_INVALIDATE_RANGE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT)) == 0;
        glGenBuffers(1, &staging_);
        glBindBuffer(GL_COPY_WRITE_BUFFER, staging_);
        glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr,
                     reads ? GL_STREAM_READ : GL_STREAM_DRAW);
        if (keeps) {
            glBindBuffer(GL_COPY_READ_BUFFER, buffer);
            glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(offset), 0,
                                static_cast<GLsizeiptr>(bytes));
            glBindBuffer(GL_COPY_READ_BUFFER, 0);
            transfers.stats.staged_bytes += bytes;
        }
        mapped = staging_;
        at = 0;
    } else {
        ++transfers.stats.in_place_maps;
        if (access & GL_MAP_WRITE_BIT) ++transfers.stats.in_place_writes;
    }
    glBindBuffer(GL_COPY_WRITE_BUFFER, mapped);
    data_ = glMapBufferRange(GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(at), static_cast<GLsizeiptr>(bytes), access);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    if (!data_) release_staging();
}

bool MappedRange::unmap() {
    if (!data_) return true;
    data_ = nullptr;
    glBindBuffer(GL_COPY_WRITE_BUFFER, staging_ ? staging_ : buffer_);
    const bool kept = glUnmapBuffer(GL_COPY_WRITE_BUFFER) == GL_TRUE;
    if (staging_ && kept) {  // (only maps that write are staged)
        glBindBuffer(GL_COPY_READ_BUFFER, staging_);
        glBindBuffer(GL_COPY_WRITE_BUFFER, buffer_);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, static_cast<GLintptr>(offset_),
                            static_cast<GLsizeiptr>(bytes_));
        glBindBuffer(GL_COPY_READ_BUFFER, 0);
        transfers_.stats.staged_bytes += bytes_;
    }
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    release_staging();
    return kept;
}

void MappedRange::release_staging() {
    if (staging_) glDeleteBuffers(1, &staging_);
    staging_ = 0;
}

}  // namespace body::render
