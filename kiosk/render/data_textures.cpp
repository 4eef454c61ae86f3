// Data textures of the line styles: allocation, row-wise upload and release.
#include "kiosk/render/data_textures.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "kiosk/render/gl_util.h"

namespace body::render {

GLuint make_data_texture(GLenum internal, size_t capacity) {
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    size_t rows = (capacity + kTextureWidth - 1) / kTextureWidth;
    glTexStorage2D(GL_TEXTURE_2D, 1, internal, kTextureWidth, static_cast<GLsizei>(std::max<size_t>(rows, 1)));
    return tex;
}

void texture_rows(GLuint tex, size_t begin, size_t end, GLenum format, GLenum type, const uint8_t* src,
                  size_t element_size) {
    const size_t begin0 = begin;
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const size_t w = kTextureWidth;
    while (begin < end) {
        size_t row = begin / w, col = begin % w;
        size_t count = std::min(end - begin, w - col);
        if (col == 0 && count == w) {
            size_t rows = (end - begin) / w;
            glTexSubImage2D(GL_TEXTURE_2D, 0, 0, static_cast<GLint>(row), static_cast<GLsizei>(w),
                            static_cast<GLsizei>(rows), format, type, src + (begin - begin0) * element_size);
            begin += rows * w;
            continue;
        }
        glTexSubImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(col), static_cast<GLint>(row), static_cast<GLsizei>(count),
                        1, format, type, src + (begin - begin0) * element_size);
        begin += count;
    }
}

void bind_data_texture(Program& p, const char* sampler, GLuint texture, int unit) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, texture);
    glUniform1i(p.loc(sampler), unit);
}

void set_quantization(Program& p, const Vec3f& origin, const Vec3f& scale) {
    glUniform3fv(p.loc("u_quant_origin"), 1, glm::value_ptr(origin));
    glUniform3fv(p.loc("u_quant_scale"), 1, glm::value_ptr(scale));
}

// A model is drawn in one style at a time, so it keeps the lazily built data of
// one line style only: building the `lines` edge texture frees the `wireframe`
// position textures and the other way round. Switching back rebuilds them from
// the GL buffers.
void free_wire_textures(Model& m) {
    if (!m.position_texture) return;
    GLuint textures[] = {m.position_texture, m.position_texture_z};
    glDeleteTextures(2, textures);
    m.position_texture = m.position_texture_z = 0;
    m.wire_stale = true;
    trim_heap();  // software drivers keep textures in host memory: hand it back before the other style builds
}

void free_edge_texture(Model& m) {
    if (!m.edge_texture) return;
    glDeleteTextures(1, &m.edge_texture);
    m.edge_texture = 0;
    m.edge_capacity = m.edge_count = 0;
    m.edges_stale = true;
    trim_heap();
}

}  // namespace body::render
