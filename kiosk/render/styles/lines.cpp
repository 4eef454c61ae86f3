// `lines` (thesis "hand-drawn 1"): a paper-white fill (mesh.vert +
// baseline.frag) and silhouette, boundary and crease edges as screen-space
// rectangles of constant pixel width (lines.vert + lines.frag; McGuire &
// Hughes 2004, edge templates without geometry shaders). The edges come from
// the model's edge texture, built here from its GL buffers when first drawn.
#include <GLES3/gl3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "kiosk/render/data_textures.h"
#include "kiosk/render/edge_list.h"
#include "kiosk/render/gl_formats.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/styles/styles.h"

namespace body::render {
namespace {

constexpr size_t kQuadEdges = 4096;  // edges per draw (16-bit indices)

// An edge record with the octahedral codes of its two face normals.
struct CodedEdge {
    EdgeRecord e;
    uint32_t n0, n1;
};

// Classifies and encodes the edges of one model, read from its mapped buffers.
struct EdgeEncoder {
    const MappedPositions& positions;
    Vec3f origin, extent;  // the box of the edge endpoints
    Vec3f step;            // the model's position code step (0: float positions)

    Vec3f face_normal(uint32_t a, uint32_t b, uint32_t c) const {
        Vec3f n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
        float l = glm::length(n);
        return l > 0.0f ? n / l : Vec3f(0.0f, 0.0f, 1.0f);
    }
    CodedEdge classify(const EdgeRecord& e) const {
        const Vec3f n0 = face_normal(e.v0, e.v1, e.a);
        const uint32_t c0 = pack_normal_code(n0);
        const uint32_t c1 = pack_normal_code(e.b == kNoVertex ? -n0 : face_normal(e.v1, e.v0, e.b));
        return CodedEdge{e, c0, c1};
    }
    // Edges between coplanar faces can never be drawn: both faces face the eye
    // alike (no silhouette) and the dihedral angle is zero (no crease at any
    // threshold above 0). They are left out, which takes most of a flat or
    // finely subdivided region's edges off the GPU: faces with the same normal
    // code, and faces whose normals differ by no more than the rounding of
    // their corners to the 16-bit position codes can tilt them.
    bool drawable(const CodedEdge& c) const {
        return c.e.b == kNoVertex ||
               (c.n0 != c.n1 && !coplanar_within_rounding(positions[c.e.v0], positions[c.e.v1], positions[c.e.a],
                                                          positions[c.e.b], step));
    }
    glm::uvec3 code(const Vec3f& p) const {
        return glm::uvec3(box_code(p.x, origin.x, extent.x), box_code(p.y, origin.y, extent.y),
                          box_code(p.z, origin.z, extent.z));
    }
    GpuEdge encode(const CodedEdge& c) const {
        const glm::uvec3 c0 = code(positions[c.e.v0]), c1 = code(positions[c.e.v1]);
        return GpuEdge{c0.x | (c0.y << 16), c0.z | (c1.x << 16), c1.y | (c1.z << 16), c.n0 | (c.n1 << 16)};
    }
};

// Box of the edge endpoints, i.e. of the non-degenerate faces' corners:
// vertices the level does not use do not change the codes.
Aabb edge_box(std::span<const uint32_t> indices, const MappedPositions& positions) {
    Aabb box;
    for (size_t f = 0; f + 2 < indices.size(); f += 3) {
        const uint32_t a = indices[f], b = indices[f + 1], c = indices[f + 2];
        if (a == b || b == c || a == c) continue;
        for (uint32_t v : {a, b, c}) box.extend(Vec3(positions[v]));
    }
    return box;
}

// A first walk counts the edges kept so that the texture is sized to them; the
// second (the same records again) converts and uploads them a chunk at a time.
void upload_edges(Model& m, std::span<const uint32_t> indices, const EdgeEncoder& encoder) {
    // 256 KiB of walk scratch and 128 KiB of records: they are alive while
    // the texture is filled, the first frame's peak in `lines`.
    EdgeStream stream(indices, size_t{256} << 10);
    constexpr size_t kEdgeChunk = 4 * kTextureWidth;
    std::vector<EdgeRecord> chunk(std::min(kEdgeChunk, std::max<size_t>(indices.size(), 1)));  // edges <= corners
    size_t kept = 0;
    while (const size_t n = stream.next(chunk))
        for (size_t i = 0; i < n; ++i) kept += encoder.drawable(encoder.classify(chunk[i]));
    m.edge_count = kept;
    if (m.edge_count > m.edge_capacity || !m.edge_texture) {
        if (m.edge_texture) glDeleteTextures(1, &m.edge_texture);
        m.edge_capacity = std::max<size_t>(m.edge_count, 1);
        m.edge_texture = make_data_texture(GL_RGBA32UI, m.edge_capacity);
    }
    stream.restart();
    size_t first = 0;
    while (const size_t n = stream.next(chunk)) {
        size_t out = 0;  // kept records are written over the chunk's front, in order
        for (size_t i = 0; i < n; ++i) {
            const CodedEdge c = encoder.classify(chunk[i]);
            if (!encoder.drawable(c)) continue;
            const GpuEdge g = encoder.encode(c);
            std::memcpy(&chunk[out++], &g, sizeof(g));
        }
        texture_rows(m.edge_texture, first, first + out, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                     reinterpret_cast<const uint8_t*>(chunk.data()), sizeof(GpuEdge));
        first += out;
    }
}

// The edge texture, rebuilt when the mesh changed. The index and position
// buffers are mapped for reading (MappedBuffer) and the records are streamed:
// built, converted to GpuEdges and uploaded a chunk at a time, so the
// transient CPU memory is the edge walk's window scratch (EdgeStream) and one
// chunk (plus, on a discrete GPU, the driver's host copy of the two buffers).
void ensure_edges(Model& m) {
    if (!m.edges_stale && m.edge_texture) return;
    static_assert(sizeof(EdgeRecord) == sizeof(GpuEdge));
    free_wire_textures(m);
    // Freed heap given back before the walk's scratch and the texture arrive,
    // whether or not position textures went (wireframe's buffer texture has
    // none; the previous style's first frame leaves driver scratch behind).
    trim_heap();
    // Mapping is per buffer: both stay mapped while the other target binding moves on.
    MappedBuffer<uint32_t> index_map(m, m.ebo, m.index_count);
    const MappedPositions positions(m);
    const std::span<const uint32_t> indices = index_map.data();
    if (indices.size() != m.index_count || !positions.ok()) {
        m.edge_count = 0;  // mapping failed: no lines this time, retried on the next frame
        return;
    }
    const Aabb box = edge_box(indices, positions);
    m.edge_origin = box.empty() ? Vec3f(0.0f) : Vec3f(box.min);
    const Vec3f extent = box.empty() ? Vec3f(0.0f) : Vec3f(box.max - box.min);
    m.edge_scale = extent / 65535.0f;
    upload_edges(m, indices, EdgeEncoder{positions, m.edge_origin, extent, m.quantized ? m.pos_scale : Vec3f(0.0f)});
    m.edges_stale = false;
    trim_heap();  // the walk's scratch back to the system
}

// Edge rectangles: one triangle per edge (lines.vert), gl_VertexID =
// u_vertex_base + the index, drawn in chunks of kQuadEdges through one shared
// 16-bit index buffer.
void draw_edge_quads(const Frame& f, Program& p, GLuint quad_vao, size_t edges) {
    glBindVertexArray(quad_vao);
    const GLint base = p.loc("u_vertex_base");
    size_t since_flush = 0;
    for (size_t first = 0; first < edges; first += kQuadEdges) {
        const size_t n = std::min(kQuadEdges, edges - first);
        glUniform1i(base, static_cast<GLint>(first * 4));
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(n * 3), GL_UNSIGNED_SHORT, nullptr);
        since_flush += n;
        if (f.flush_large_draws && since_flush >= kFlushTriangles) {
            f.pacer->flush();  // bounds the software rasterizer's bins (see kFlushTriangles)
            since_flush = 0;
        }
    }
}

}  // namespace

void create_edge_quads(RendererState& s) {
    std::vector<uint16_t> quads;  // one triangle per edge: corners 4e, 4e + 1, 4e + 2 (see lines.vert)
    quads.reserve(kQuadEdges * 3);
    for (size_t e = 0; e < kQuadEdges; ++e) {
        const auto c = static_cast<uint16_t>(e * 4);
        quads.insert(quads.end(), {c, static_cast<uint16_t>(c + 1), static_cast<uint16_t>(c + 2)});
    }
    glGenVertexArrays(1, &s.quad_vao);
    glBindVertexArray(s.quad_vao);
    glGenBuffers(1, &s.quad_ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.quad_ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(quads.size() * sizeof(uint16_t)), quads.data(),
                 GL_STATIC_DRAW);
    glBindVertexArray(0);
}

void draw_lines(RendererState& s, Frame& f, Model& m) {
    const FrameOptions& o = *f.options;
    glEnable(GL_POLYGON_OFFSET_FILL);  // the paper fill behind the edges it outlines
    glPolygonOffset(1.0f, 1.0f);
    draw_coloured(f, s.programs.baseline, m, o.paper, false);
    glDisable(GL_POLYGON_OFFSET_FILL);
    ensure_edges(m);
    Program& p = s.programs.lines;
    f.use(p);
    glm::mat4 mvp = f.projection * f.view * m.state.transform;
    Vec3f eye_object = Vec3f(glm::inverse(m.state.transform) * glm::vec4(f.camera->eye, 1.0f));
    glUniformMatrix4fv(p.loc("u_model_view_projection"), 1, GL_FALSE, glm::value_ptr(mvp));
    glUniform3fv(p.loc("u_eye_object"), 1, glm::value_ptr(eye_object));
    glUniform1f(p.loc("u_cos_crease"), std::cos(glm::radians(o.crease_angle_deg)));
    glUniform2f(p.loc("u_viewport"), static_cast<float>(o.width), static_cast<float>(o.height));
    glUniform1f(p.loc("u_width_px"), o.line_width_px);
    glUniform4f(p.loc("u_color"), o.ink.r, o.ink.g, o.ink.b, 1.0f);
    set_quantization(p, m.edge_origin, m.edge_scale);
    bind_data_texture(p, "u_edges", m.edge_texture, 0);
    glDisable(GL_CULL_FACE);
    draw_edge_quads(f, p, s.quad_vao, m.edge_count);
    glEnable(GL_CULL_FACE);
    s.stats.edges += m.edge_count;
    ++s.stats.draw_calls;
}

}  // namespace body::render
