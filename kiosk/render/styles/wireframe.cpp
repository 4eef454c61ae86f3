// `wireframe`: barycentric edges of constant pixel width in the fragment
// shader over lightly flat-shaded faces (GLES has no polygon mode); shaders
// wireframe.vert + wireframe.frag. The vertex positions come from the model's
// position buffer through a buffer texture where the driver offers them and
// the positions are codes, else from position textures built here from its GL
// buffers when first drawn.
#include <GLES3/gl32.h>

#include <algorithm>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "kiosk/render/data_textures.h"
#include "kiosk/render/gl_formats.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/styles/styles.h"

namespace body::render {
namespace {

// The position textures, rebuilt (in place) when the vertices changed: per
// vertex its position as 16-bit codes in the box of the drawn vertices, x and
// y in an RG16UI texel and z in an R16UI one (6 bytes; one RGB16UI texel is 8
// on llvmpipe, which has no 48-bit format). The indices need no texture (see
// draw_wire_chunks). Built in pieces from the mapped buffer, so the only
// scratch is one piece.
void ensure_wire_positions(Model& m) {
    if (!m.wire_stale && m.position_texture) return;
    free_edge_texture(m);
    if (!m.position_texture) {
        m.position_texture = make_data_texture(GL_RG16UI, m.vertex_capacity);
        m.position_texture_z = make_data_texture(GL_R16UI, m.vertex_capacity);
    }
    const MappedPositions positions(m);
    if (!positions.ok()) return;  // retried next frame
    constexpr size_t kPiece = 16 * kTextureWidth;
    std::vector<uint16_t> xy(std::min(kPiece, positions.size()) * 2), z(xy.size() / 2);
    // Quantized: the buffer's codes are the texture's; else codes in the box
    // of the drawn vertices.
    Vec3f extent(0.0f);
    if (m.quantized) {
        m.wire_origin = m.pos_origin;
        m.wire_scale = m.pos_scale;
    } else {
        Aabb box;
        for (size_t v = 0; v < positions.size(); ++v) box.extend(Vec3(positions[v]));
        m.wire_origin = box.empty() ? Vec3f(0.0f) : Vec3f(box.min);
        extent = box.empty() ? Vec3f(0.0f) : Vec3f(box.max - box.min);
        m.wire_scale = extent / 65535.0f;
    }
    for (size_t first = 0; first < positions.size(); first += kPiece) {
        const size_t n = std::min(kPiece, positions.size() - first);
        for (size_t i = 0; i < n; ++i) {
            if (m.quantized) {
                const uint16_t* c = positions.codes() + (first + i) * 3;
                xy[i * 2] = c[0];
                xy[i * 2 + 1] = c[1];
                z[i] = c[2];
            } else {
                const Vec3f p = positions[first + i];
                xy[i * 2] = box_code(p.x, m.wire_origin.x, extent.x);
                xy[i * 2 + 1] = box_code(p.y, m.wire_origin.y, extent.y);
                z[i] = box_code(p.z, m.wire_origin.z, extent.z);
            }
        }
        texture_rows(m.position_texture, first, first + n, GL_RG_INTEGER, GL_UNSIGNED_SHORT,
                     reinterpret_cast<const uint8_t*>(xy.data()), 4);
        texture_rows(m.position_texture_z, first, first + n, GL_RED_INTEGER, GL_UNSIGNED_SHORT,
                     reinterpret_cast<const uint8_t*>(z.data()), 2);
    }
    m.wire_stale = false;
}

// The triangles are drawn unindexed, three vertices each, with the model's
// index buffer bound as the integer attribute kWireVertex: vertex i of the
// draw gets index i, i.e. the mesh vertex of that corner, and i % 3 is the
// corner. Issued in chunks, the attribute re-pointed at each chunk's first
// index and gl_VertexID counting from 0 in each: softpipe (Mesa's reference
// driver, the aarch64 cross smoke's) restarts gl_VertexID in the pieces it
// splits long draws into, which drops most of a large model.
constexpr size_t kVertexIdChunk = 3 * 1024;
void draw_wire_chunks(const Frame& f, GLuint vao, GLuint index_buffer, size_t vertices) {
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, index_buffer);
    size_t since_flush = 0;
    for (size_t first = 0; first < vertices; first += kVertexIdChunk) {
        glVertexAttribIPointer(kWireVertex, 1, GL_UNSIGNED_INT, sizeof(uint32_t),
                               reinterpret_cast<const void*>(first * sizeof(uint32_t)));
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(std::min(kVertexIdChunk, vertices - first)));
        since_flush += kVertexIdChunk / 3;
        if (f.flush_large_draws && since_flush >= kFlushTriangles) {
            f.pacer->flush();  // bounds the software rasterizer's bins (see kFlushTriangles)
            since_flush = 0;
        }
    }
}

// The buffer texture over the model's position codes (3 R16UI texels a
// vertex), attached again when the buffer was replaced (buffer_growth.h).
// Nothing is copied: the texture reads the buffer, so it never goes stale and
// adds no memory (the position textures took 6 bytes a vertex, built while
// the level's buffers were held). False where it cannot serve this model:
// not offered, float positions, more texels than the driver allows, or
// the program does not link (then the position textures are used).
bool wire_buffer_texture(RendererState& s, Frame& f, Model& m) {
    if (!m.quantized || s.wire_buffer_texels == 0 || m.vertex_allocated * 3 > s.wire_buffer_texels) return false;
    Program& p = s.programs.wireframe_buffer;
    if (!p.id) {
        if (!link_on_first_use(p)) {
            s.wire_buffer_texels = 0;  // not again
            return false;
        }
        ++f.programs_linked;
    }
    if (!m.position_buffer_texture) glGenTextures(1, &m.position_buffer_texture);
    if (m.position_buffer_of != m.vbo_position || m.position_buffer_vertices != m.vertex_allocated) {
        glBindTexture(GL_TEXTURE_BUFFER, m.position_buffer_texture);
        glTexBuffer(GL_TEXTURE_BUFFER, GL_R16UI, m.vbo_position);
        glBindTexture(GL_TEXTURE_BUFFER, 0);
        m.position_buffer_of = m.vbo_position;
        m.position_buffer_vertices = m.vertex_allocated;
    }
    free_wire_textures(m);  // left from before a change to float positions and back, if any
    free_edge_texture(m);   // one line style's data at a time (data_textures.h)
    return true;
}

}  // namespace

void create_wire_vertex_array(RendererState& s, bool buffer_texture) {
    glGenVertexArrays(1, &s.wire_vao);
    glBindVertexArray(s.wire_vao);
    glEnableVertexAttribArray(kWireVertex);
    glBindVertexArray(0);
    // GLES 3.2 (buffer textures in core and in GLSL ES 3.20; GLSL ES 3.00
    // shaders cannot enable GL_EXT_texture_buffer).
    if (buffer_texture && gl_version_at_least(3, 2)) {
        GLint texels = 0;
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
        s.wire_buffer_texels = texels > 0 ? static_cast<size_t>(texels) : 0;
    }
}

void draw_wireframe(RendererState& s, Frame& f, Model& m) {
    const FrameOptions& o = *f.options;
    const Vec3f col = m.state.color;
    const bool buffer = wire_buffer_texture(s, f, m);
    if (!buffer) ensure_wire_positions(m);
    Program& p = buffer ? s.programs.wireframe_buffer : s.programs.wireframe;
    f.use(p);
    set_matrices(p, f, m);
    set_lights(p, f);
    glUniform4f(p.loc("u_color"), col.r, col.g, col.b, 1.0f);
    glUniform1f(p.loc("u_width_px"), o.line_width_px * 0.75f);
    if (buffer) {
        // The buffer's codes in the model's box: the same values the position textures held.
        set_quantization(p, m.pos_origin, m.pos_scale);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_BUFFER, m.position_buffer_texture);
        glUniform1i(p.loc("u_position_codes"), 0);
    } else {
        set_quantization(p, m.wire_origin, m.wire_scale);
        bind_data_texture(p, "u_positions", m.position_texture, 0);
        bind_data_texture(p, "u_positions_z", m.position_texture_z, 1);
        glActiveTexture(GL_TEXTURE0);
    }
    draw_wire_chunks(f, s.wire_vao, m.ebo, m.index_count);
}

}  // namespace body::render
