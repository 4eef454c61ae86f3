// BodyView's GLES 3.0 renderer: buffers per model, the five styles, selection
// and x-ray, depth-correct mixing. References: thesis section 3.4 (silhouette
// and detail lines; multi-texture hatching after Lake et al. 2000); McGuire &
// Hughes 2004 (edge templates); Praun et al. 2001 and Webb et al. 2002 (tonal
// art maps); Blinn 1977 (specular). Layout after Dear ImGui's
// imgui_impl_opengl3.cpp: one state struct, init/shutdown/render.
#include "kiosk/render/renderer.h"

#include <GLES3/gl3.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>

#include "kiosk/render/edge_list.h"
#include "kiosk/render/tonal_art_map.h"
#include "shared/pm/quantize.h"

namespace body::render {

#ifdef BODY_GL_DEBUG
#define BODY_GL_CHECK(where)                                                                               \
    do {                                                                                                   \
        for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError())                                  \
            std::fprintf(stderr, "bodyview: GL error 0x%04x after %s\n", static_cast<unsigned>(e), where); \
    } while (0)
#else
#define BODY_GL_CHECK(where) \
    do {                     \
    } while (0)
#endif

namespace {

// Texels per row of the data textures (the GLES 3.0 minimum); edges.vert and
// wireframe.vert hold it as a constant (a shift, not a division).
constexpr int kTextureWidth = 2048;
constexpr GLuint kPosition = 0, kNormal = 1, kMorph = 2;
constexpr GLuint kWireVertex = 3;  // `wireframe`: the index buffer read as a vertex attribute
constexpr GLuint kNormalCode = 4;  // 8:8 octahedral normal codes (mesh.vert decodes them)

// Software rasterizers (llvmpipe) bin every triangle of a frame before
// rasterizing it, about 130 bytes per covered triangle plus 48 per varying, and
// keep that memory: a million-triangle model held ~75 MiB of bins. Flushing
// after every kFlushTriangles, and waiting for the scene before (FlushPacer),
// bounds it to two scenes of that size (4K: ~0.5 MiB of bins each; 8K held
// 1.2-1.9 MiB more in every style's frame of the 1.1M bunny, with the same
// ratios to the baseline) (tilers on real GPUs would pay a tile resolve per
// flush, so only software drivers do it).
constexpr size_t kFlushTriangles = 4 * 1024;
bool g_flush_large_draws = false;  // set by init() from GL_RENDERER

// A flush alone lets the application run ahead of the rasterizer threads, and
// every queued scene keeps its bins: how many depends on the machine's load.
// Waiting for the scene before the last one keeps at most two in flight (one
// binning, one rasterizing), so the working memory no longer depends on timing.
class FlushPacer {
public:
    FlushPacer() = default;
    FlushPacer(const FlushPacer&) = delete;
    FlushPacer& operator=(const FlushPacer&) = delete;
    ~FlushPacer() {
        if (previous_) glDeleteSync(previous_);
    }
    void flush() {
        GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        glFlush();
        if (previous_) {
            glClientWaitSync(previous_, 0, GL_TIMEOUT_IGNORED);
            glDeleteSync(previous_);
        }
        previous_ = fence;
    }

private:
    GLsync previous_ = nullptr;
};
constexpr size_t kQuadEdges = 4096;  // edges per draw of the `lines` style (16-bit indices)

struct Program {
    GLuint id = 0;
    bool drawn = false;  // used by a frame already (its shader variants compiled)
    std::map<std::string, GLint> locations;
    GLint loc(const char* name) {
        auto it = locations.find(name);
        if (it != locations.end()) return it->second;
        GLint l = glGetUniformLocation(id, name);
        locations.emplace(name, l);
        return l;
    }
};

// How models' buffers are written (BufferAccess), and what the maps moved
// (Renderer::State holds one; each model points to it).
struct Transfers {
    bool staged = false;  // BufferAccess::Staged, as init() resolved it
    TransferStats stats;
};

struct Model {
    std::string name;
    Transfers* transfers = nullptr;  // the renderer's (add_model)
    ModelState state;
    GLuint vao = 0, vbo_position = 0, vbo_normal = 0, ebo = 0;
    GLuint vbo_morph = 0;  // geomorph sources (progressive meshes only)
    // Normals in GL: the source's 8:8 octahedral codes as they are (2 bytes a
    // vertex, decoded in mesh.vert) when add_model got codes, else
    // GL_INT_2_10_10_10_REV (4 bytes).
    bool normal_codes = false;
    size_t normal_stride() const { return normal_codes ? 2 : 4; }
    // Positions (and morph sources) in GL: 16-bit codes per axis in a box fixed
    // at add_model (object = pos_origin + pos_scale * code, 6 bytes a vertex),
    // or floats (12 bytes) when the box is not known or a patch left it.
    bool quantized = false;
    Vec3f pos_origin{0.0f}, pos_scale{1.0f};
    size_t position_stride() const { return quantized ? 6 : sizeof(Vec3f); }
    size_t vertex_capacity = 0, index_capacity = 0;
    size_t vertex_count = 0, index_count = 0;
    Vec3f center{0.0f};
    float radius = 0.0f;
    Vec3f box_min{0.0f}, box_max{0.0f};  // object space
    // Lazily created: the position texture for `wireframe`, the edge texture for `lines`.
    // `wireframe`: x and y codes in RG16UI, z in R16UI (6 bytes a vertex; an
    // RGB16UI texture is padded to 8 by llvmpipe).
    GLuint position_texture = 0, position_texture_z = 0;
    Vec3f wire_origin{0.0f}, wire_scale{0.0f};  // dequantization of the position texture
    bool wire_stale = true;
    GLuint edge_texture = 0;                    // RGBA32UI, one GpuEdge per texel
    Vec3f edge_origin{0.0f}, edge_scale{0.0f};  // dequantization of the GpuEdge endpoints
    size_t edge_capacity = 0;
    size_t edge_count = 0;
    bool edges_stale = true;
    bool internal = false;  // the manipulation sphere
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
    MappedRange(Transfers& transfers, GLuint buffer, size_t offset, size_t bytes, GLbitfield access)
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
        data_ =
            glMapBufferRange(GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(at), static_cast<GLsizeiptr>(bytes), access);
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
        if (!data_) release_staging();
    }
    ~MappedRange() { (void)unmap(); }
    MappedRange(const MappedRange&) = delete;
    MappedRange& operator=(const MappedRange&) = delete;

    // Null when the mapping failed (or the range is empty).
    void* data() const { return data_; }
    // Ends the mapping (staged and written: copies the range back). False when
    // the driver lost the store while mapped (GL_FALSE from glUnmapBuffer, e.g.
    // a display mode change): the range's contents are undefined.
    bool unmap() {
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

private:
    void release_staging() {
        if (staging_) glDeleteBuffers(1, &staging_);
        staging_ = 0;
    }
    Transfers& transfers_;
    GLuint buffer_, staging_ = 0;
    size_t offset_, bytes_;
    void* data_ = nullptr;
};

uint32_t pack_normal(const Vec3f& n) {
    auto q = [](float v) {
        int i = static_cast<int>(std::lround(std::clamp(v, -1.0f, 1.0f) * 511.0f));
        return static_cast<uint32_t>(i) & 0x3ffu;
    };
    return q(n.x) | (q(n.y) << 10) | (q(n.z) << 20);
}

// Unit vector -> 8:8 signed octahedral code, x in the low byte (Meyer et al.
// 2010, "On floating-point normal vectors").
uint32_t pack_octahedral(const Vec3f& n) {
    const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    glm::vec2 p = l1 > 0.0f ? glm::vec2(n.x, n.y) / l1 : glm::vec2(0.0f);
    if (n.z < 0.0f) {
        const glm::vec2 s(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
        p = (1.0f - glm::abs(glm::vec2(p.y, p.x))) * s;
    }
    auto q = [](float v) {
        return static_cast<uint32_t>(static_cast<int>(std::lround(std::clamp(v, -1.0f, 1.0f) * 127.0f))) & 0xffu;
    };
    return q(p.x) | (q(p.y) << 8);
}

// The positions of an upload: floats, or 16-bit codes in a box (MeshData::
// position_codes), indexed by vertex number (a view of morph sources from
// `first` on starts there).
class PositionView {
public:
    explicit PositionView(std::span<const Vec3f> f, size_t first = 0) : f_(f), first_(first), n_(first + f.size()) {}
    explicit PositionView(const MeshData& mesh) : f_(mesh.positions), n_(mesh.positions.size()) {
        if (mesh.position_codes.empty()) return;
        q_ = mesh.position_codes;
        n_ = q_.size() / 3;
        origin_ = mesh.position_box_min;
        scale_ = (mesh.position_box_max - mesh.position_box_min) / 65535.0f;
    }
    size_t size() const { return n_; }  // vertices, counting from 0
    bool empty() const { return n_ == 0; }
    bool coded() const { return !q_.empty(); }
    Vec3f origin() const { return origin_; }
    Vec3f scale() const { return scale_; }
    const uint16_t* codes(size_t v) const { return q_.data() + (v - first_) * 3; }
    const Vec3f* floats(size_t v) const { return f_.data() + (v - first_); }
    Vec3f operator[](size_t v) const {
        if (q_.empty()) return f_[v - first_];
        const uint16_t* c = codes(v);
        return origin_ + scale_ * Vec3f(c[0], c[1], c[2]);
    }

private:
    std::span<const Vec3f> f_;
    std::span<const uint16_t> q_;
    size_t first_ = 0, n_ = 0;
    Vec3f origin_{0.0f}, scale_{1.0f};
};

std::vector<Vec3f> area_normals(const PositionView& p, std::span<const uint32_t> idx, size_t vertex_count) {
    std::vector<Vec3f> n(vertex_count, Vec3f(0.0f));
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
        uint32_t a = idx[f], b = idx[f + 1], c = idx[f + 2];
        if (a >= vertex_count || b >= vertex_count || c >= vertex_count) continue;
        Vec3f fn = glm::cross(p[b] - p[a], p[c] - p[a]);
        n[a] += fn;
        n[b] += fn;
        n[c] += fn;
    }
    for (auto& v : n) {
        float l = glm::length(v);
        v = l > 0.0f ? v / l : Vec3f(0.0f, 0.0f, 1.0f);
    }
    return n;
}

// Frees the upload's normal scratch and, when it was large, hands it back to the
// system (glibc keeps big freed blocks resident once its mmap threshold grew).
void release_scratch(std::vector<Vec3f>& computed) {
    const bool large = computed.capacity() * sizeof(Vec3f) >= (1u << 20);
    // Swapped out, not `= {}`: that picks the initializer_list assignment, which
    // empties the vector but keeps its storage.
    std::vector<Vec3f>().swap(computed);
#ifdef __GLIBC__
    if (large) malloc_trim(0);
#else
    (void)large;
#endif
}

// Writes normals [begin, end) into the GL_ARRAY_BUFFER bound in the model's
// format (Model::normal_codes): octahedral `codes` (two per vertex) as they
// are, anything else converted a piece at a time (no converted copy of the
// whole range is held). From `codes` when given, else from `normals`.
void upload_normals(const Model& m, std::span<const Vec3f> normals, std::span<const uint8_t> codes, size_t begin,
                    size_t end) {
    if (begin >= end) return;
    if (m.normal_codes && !codes.empty()) {
        glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(begin * 2), static_cast<GLsizeiptr>((end - begin) * 2),
                        codes.data() + begin * 2);
        return;
    }
    constexpr size_t kPiece = 64 * 1024;
    const size_t stride = m.normal_stride();
    std::vector<uint32_t> piece(std::min(kPiece, end - begin));  // 4 bytes a vertex holds either format
    for (size_t first = begin; first < end; first += kPiece) {
        const size_t n = std::min(kPiece, end - first);
        for (size_t i = 0; i < n; ++i) {
            Vec3f v;
            if (codes.empty()) {
                v = normals[first + i];
            } else {
                float d[3];
                pm::oct_decode8(&codes[(first + i) * 2], d);
                v = Vec3f(d[0], d[1], d[2]);
            }
            if (m.normal_codes)
                pm::oct_encode8(v.x, v.y, v.z, reinterpret_cast<uint8_t*>(piece.data()) + i * 2);
            else
                piece[i] = pack_normal(v);
        }
        glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(first * stride), static_cast<GLsizeiptr>(n * stride),
                        piece.data());
    }
}

// Writes indices [begin, end) into the GL_ELEMENT_ARRAY_BUFFER bound, a piece
// at a time, telling `uploaded` (MeshData::indices_uploaded) after each piece.
void upload_indices(const MeshData& mesh, size_t begin, size_t end,
                    const std::function<void(size_t)>& uploaded = nullptr) {
    constexpr size_t kPiece = 256 * 1024;  // 1 MiB
    for (size_t first = begin; first < end; first += kPiece) {
        const size_t n = std::min(kPiece, end - first);
        glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLintptr>(first * 4), static_cast<GLsizeiptr>(n * 4),
                        mesh.indices.data() + first);
        if (uploaded) uploaded(first + n);
    }
}

// The 16-bit code of p in the model's position box (clamped to it).
glm::u16vec3 position_code(const Model& m, const Vec3f& p) {
    glm::u16vec3 c(0);
    for (int k = 0; k < 3; ++k)
        if (m.pos_scale[k] > 0.0f)
            c[k] = static_cast<uint16_t>(
                std::lround(std::clamp((p[k] - m.pos_origin[k]) / m.pos_scale[k], 0.0f, 65535.0f)));
    return c;
}

// Whether every position of [begin, end) has a code within half a step (the
// box a quantized model was given still holds them).
bool inside_position_box(const Model& m, const PositionView& positions, size_t begin, size_t end) {
    const Vec3f lo = m.pos_origin - m.pos_scale * 0.5f - Vec3f(1e-6f),
                hi = m.pos_origin + m.pos_scale * 65535.5f + Vec3f(1e-6f);
    for (size_t i = begin; i < end; ++i)
        if (glm::any(glm::lessThan(positions[i], lo)) || glm::any(glm::greaterThan(positions[i], hi))) return false;
    return true;
}

// Writes the positions of vertices [begin, end) into the GL_ARRAY_BUFFER
// bound, in the model's format: codes in the model's box as they are,
// anything else converted a piece at a time.
void upload_positions(const Model& m, const PositionView& src, size_t begin, size_t end) {
    if (begin >= end) return;
    if (m.quantized && src.coded() && src.origin() == m.pos_origin && src.scale() == m.pos_scale) {
        glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(begin * 6), static_cast<GLsizeiptr>((end - begin) * 6),
                        src.codes(begin));
        return;
    }
    if (!m.quantized && !src.coded()) {
        glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(begin * sizeof(Vec3f)),
                        static_cast<GLsizeiptr>((end - begin) * sizeof(Vec3f)), src.floats(begin));
        return;
    }
    constexpr size_t kPiece = 64 * 1024;
    static_assert(sizeof(glm::u16vec3) == 6);
    const size_t stride = m.position_stride();
    std::vector<uint8_t> piece(std::min(kPiece, end - begin) * stride);
    for (size_t first = begin; first < end; first += kPiece) {
        const size_t n = std::min(kPiece, end - first);
        for (size_t i = 0; i < n; ++i) {
            if (m.quantized) {
                const glm::u16vec3 c = position_code(m, src[first + i]);
                std::memcpy(piece.data() + i * stride, &c, stride);
            } else {
                const Vec3f p = src[first + i];
                std::memcpy(piece.data() + i * stride, &p, stride);
            }
        }
        glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(first * stride), static_cast<GLsizeiptr>(n * stride),
                        piece.data());
    }
}

// The position (or morph) attribute of the model's format, from the buffer bound.
void position_pointer(const Model& m, GLuint location) {
    if (m.quantized)
        glVertexAttribPointer(location, 3, GL_UNSIGNED_SHORT, GL_FALSE, 6, nullptr);
    else
        glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
}

// Object-space box and bounding sphere of the drawn vertices.
void set_bounds(Model& m, const PositionView& positions, size_t count) {
    Aabb box;
    for (size_t v = 0; v < count; ++v) box.extend(Vec3(positions[v]));
    m.center = Vec3f((box.min + box.max) * 0.5);
    m.radius = static_cast<float>(box.extent() * 0.5);
    m.box_min = Vec3f(box.min);
    m.box_max = Vec3f(box.max);
}

// A shader's or program's info log on one line; the object is deleted.
std::string take_info_log(GLuint id, bool program) {
    char log[2048] = {};
    if (program) {
        glGetProgramInfoLog(id, sizeof(log), nullptr, log);
        glDeleteProgram(id);
    } else {
        glGetShaderInfoLog(id, sizeof(log), nullptr, log);
        glDeleteShader(id);
    }
    std::string one_line(log);
    std::replace(one_line.begin(), one_line.end(), '\n', ' ');
    return one_line;
}

Result<GLuint> compile(GLenum type, const char* src, const std::string& label) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) return runtime_error("shader " + label + ": compile failed: " + take_info_log(s, false));
    return s;
}

Result<Program> link(const std::string& vert, const std::string& frag) {
    const char* vs = shader_source(vert);
    const char* fs = shader_source(frag);
    if (!vs || !fs) return runtime_error("shader " + (vs ? frag : vert) + ": not embedded in this build");
    const std::pair<unsigned, const char*> attributes[] = {{kPosition, "a_position"},
                                                           {kNormal, "a_normal"},
                                                           {kMorph, "a_morph"},
                                                           {kWireVertex, "a_vertex"},
                                                           {kNormalCode, "a_normal_code"}};
    auto id = link_program(vs, fs, vert + "+" + frag, attributes);
    if (!id) return id.error();
    Program p;
    p.id = id.value();
    return p;
}

// Uploads elements [begin, end) of an array laid out kTextureWidth per row;
// `src` holds element `begin` first.
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

}  // namespace

Result<unsigned> link_program(const char* vertex_source, const char* fragment_source, const std::string& name,
                              std::span<const std::pair<unsigned, const char*>> attributes) {
    auto vs = compile(GL_VERTEX_SHADER, vertex_source, name + " (vertex)");
    if (!vs) return vs.error();
    auto fs = compile(GL_FRAGMENT_SHADER, fragment_source, name + " (fragment)");
    if (!fs) {
        glDeleteShader(vs.value());
        return fs.error();
    }
    const GLuint id = glCreateProgram();
    glAttachShader(id, vs.value());
    glAttachShader(id, fs.value());
    for (const auto& [location, attribute] : attributes) glBindAttribLocation(id, location, attribute);
    glLinkProgram(id);
    glDeleteShader(vs.value());
    glDeleteShader(fs.value());
    GLint ok = 0;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok) return runtime_error("program " + name + ": link failed: " + take_info_log(id, true));
    return id;
}

const char* style_name(Style style) {
    switch (style) {
        case Style::Smooth: return "smooth";
        case Style::Wireframe: return "wireframe";
        case Style::Lines: return "lines";
        case Style::Hatching: return "hatching";
        case Style::Hatching2Tone: return "hatching-2tone";
        case Style::Baseline: return "baseline";
    }
    return "?";
}

Result<Style> parse_style(const std::string& name) {
    for (Style s :
         {Style::Smooth, Style::Wireframe, Style::Lines, Style::Hatching, Style::Hatching2Tone, Style::Baseline})
        if (name == style_name(s)) return s;
    return input_error("unknown style '" + name + "' (expected smooth, wireframe, lines, hatching, hatching-2tone)");
}

const char* buffer_access_name(BufferAccess access) {
    switch (access) {
        case BufferAccess::InPlace: return "in-place";
        case BufferAccess::Staged: return "staged";
        case BufferAccess::Auto: break;
    }
    return "auto";
}

Result<BufferAccess> parse_buffer_access(const std::string& name) {
    for (BufferAccess a : {BufferAccess::Auto, BufferAccess::InPlace, BufferAccess::Staged})
        if (name == buffer_access_name(a)) return a;
    return input_error("unknown buffer access '" + name + "' (expected auto, in-place, staged)");
}

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }
glm::mat4 Camera::projection(float aspect) const {
    return glm::perspective(glm::radians(fov_y_deg), aspect, near_plane, far_plane);
}
Camera Camera::framing(Vec3f center, float radius, Vec3f direction) {
    Camera c;
    radius = std::max(radius, 1e-6f);
    float d = radius / std::sin(glm::radians(c.fov_y_deg) * 0.5f) * 1.02f;
    c.target = center;
    c.eye = center + glm::normalize(direction) * d;
    c.near_plane = std::max(d - radius * 1.5f, d * 0.01f);
    c.far_plane = d + radius * 1.5f;
    return c;
}

Camera Camera::framing_box(Vec3f lo, Vec3f hi, Vec3f direction, float aspect, float fov_y_deg) {
    Camera c;
    c.fov_y_deg = fov_y_deg;
    c.target = (lo + hi) * 0.5f;
    const Vec3f back = glm::normalize(direction);  // from target toward the eye
    const Vec3f right = glm::normalize(glm::cross(c.up, back));
    const Vec3f up = glm::cross(back, right);
    const float ty = std::tan(glm::radians(fov_y_deg) * 0.5f), tx = ty * aspect;
    float d = 1e-6f, reach = 0.0f;
    for (int i = 0; i < 8; ++i) {
        Vec3f corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        Vec3f o = corner - c.target;
        float toward = glm::dot(o, back);  // positive: nearer to the eye
        d = std::max({d, toward + std::abs(glm::dot(o, right)) / tx, toward + std::abs(glm::dot(o, up)) / ty});
        reach = std::max(reach, glm::length(o));
    }
    d *= 1.04f;
    c.eye = c.target + back * d;
    c.near_plane = std::max(d - reach * 1.05f, d * 0.01f);
    c.far_plane = d + reach * 1.05f;
    return c;
}

struct Renderer::State {
    bool ready = false;
    Program baseline, smooth, hatching, xray, edges, wireframe;
    GLuint tam = 0;       // tonal art map: a 2D array texture, made at the first hatching draw (create_tonal_art_map)
    GLuint wire_vao = 0;  // `wireframe`: a model's index buffer as the kWireVertex attribute
    GLuint quad_vao = 0, quad_ebo = 0;  // `lines`: the shared edge-quad index buffer
    std::map<ModelId, Model> models;
    ModelId next_id = 1;
    ModelId sphere = 0;
    FrameStats stats;
    Transfers transfers;
};

// Tonal art map (Praun et al. 2001) with our own mip chain (tone matched per
// level), packed so that every fragment needs one texture read: hatching
// blends the two tones around its light level, and layer 0 holds tones 0-3,
// layer 1 tones 2-5 (RGBA), so either layer covers any such pair (the shader
// picks the layer per fragment); layer 2 holds the two tones of the two-tone
// variant (1 and 4, in R and G). Made at the first hatching draw, not at init:
// generating the tones is ~8 ms of the kiosk's start-up (first frame goal
// 100 ms) that a scene without hatching never needs. The CPU tones are freed
// when it returns.
static void create_tonal_art_map(GLuint& texture) {
    TonalArtMap tam = make_tonal_art_map(256, 6);
    constexpr int kLayerTones[3][4] = {{0, 1, 2, 3}, {2, 3, 4, 5}, {1, 4, 4, 4}};
    const auto levels = static_cast<GLsizei>(tam.levels.size());
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, levels, GL_RGBA8, tam.size, tam.size, 3);
    for (GLsizei l = 0; l < levels; ++l) {
        const int size = std::max(1, tam.size >> l);
        const auto& tones = tam.levels[static_cast<size_t>(l)];
        std::vector<uint8_t> rgba(static_cast<size_t>(size) * static_cast<size_t>(size) * 4);
        for (int layer = 0; layer < 3; ++layer) {
            for (size_t i = 0; i < rgba.size() / 4; ++i)
                for (size_t c = 0; c < 4; ++c) rgba[i * 4 + c] = tones[static_cast<size_t>(kLayerTones[layer][c])][i];
            glTexSubImage3D(GL_TEXTURE_2D_ARRAY, l, 0, 0, layer, size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        }
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

Renderer::Renderer() : s_(std::make_unique<State>()) {}
Renderer::~Renderer() = default;

Status Renderer::init(const RendererOptions& options) {
    if (s_->ready) return ok_status();
#ifdef __GLIBC__
    // Blocks of 1 MiB and more (GL buffers and textures on software drivers,
    // upload scratch) are mapped and unmapped, whatever was freed before:
    // glibc would otherwise raise that threshold to the largest block freed
    // (up to 32 MiB) and keep freed textures resident on its heap until a
    // trim, e.g. a data texture the driver releases in the middle of the next
    // style's first frame. Process-wide, like the trims here.
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
    struct Want {
        Program* p;
        const char* vert;
        const char* frag;
    };
    for (Want w :
         {Want{&s_->baseline, "mesh.vert", "baseline.frag"}, Want{&s_->smooth, "mesh.vert", "smooth.frag"},
          Want{&s_->hatching, "mesh.vert", "hatching.frag"}, Want{&s_->xray, "mesh.vert", "xray.frag"},
          Want{&s_->edges, "edges.vert", "edges.frag"}, Want{&s_->wireframe, "wireframe.vert", "wireframe.frag"}}) {
        auto p = link(w.vert, w.frag);
        if (!p) {
            shutdown();
            return p.error();
        }
        *w.p = std::move(p.value());
    }

    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);

    glGenVertexArrays(1, &s_->wire_vao);
    glBindVertexArray(s_->wire_vao);
    glEnableVertexAttribArray(kWireVertex);
    glBindVertexArray(0);
    {
        std::vector<uint16_t> quads;  // one triangle per edge: corners 4e, 4e + 1, 4e + 2 (see edges.vert)
        quads.reserve(kQuadEdges * 3);
        for (size_t e = 0; e < kQuadEdges; ++e) {
            const auto c = static_cast<uint16_t>(e * 4);
            quads.insert(quads.end(), {c, static_cast<uint16_t>(c + 1), static_cast<uint16_t>(c + 2)});
        }
        glGenVertexArrays(1, &s_->quad_vao);
        glBindVertexArray(s_->quad_vao);
        glGenBuffers(1, &s_->quad_ebo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s_->quad_ebo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(quads.size() * sizeof(uint16_t)), quads.data(),
                     GL_STATIC_DRAW);
        glBindVertexArray(0);
    }
    const char* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    g_flush_large_draws = gl_renderer && (std::strstr(gl_renderer, "llvmpipe") || std::strstr(gl_renderer, "softpipe"));
    const char* gl_vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    const bool own_memory = gl_vendor && (std::strstr(gl_vendor, "NVIDIA") || std::strstr(gl_vendor, "AMD") ||
                                          std::strstr(gl_vendor, "ATI Technologies"));
    s_->transfers.staged =
        options.buffer_access == BufferAccess::Staged || (options.buffer_access == BufferAccess::Auto && own_memory);
    s_->transfers.stats = {};
    s_->ready = true;

    // The manipulation sphere: a UV sphere of radius 1.
    std::vector<Vec3f> sp;
    std::vector<uint32_t> si;
    const int rings = 24, segments = 48;
    for (int r = 0; r <= rings; ++r)
        for (int g = 0; g <= segments; ++g) {
            float th = glm::pi<float>() * static_cast<float>(r) / rings;
            float ph = 2.0f * glm::pi<float>() * static_cast<float>(g) / segments;
            sp.emplace_back(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
        }
    for (int r = 0; r < rings; ++r)
        for (int g = 0; g < segments; ++g) {
            uint32_t a = static_cast<uint32_t>(r * (segments + 1) + g), b = a + segments + 1;
            si.insert(si.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    auto sphere = add_model({sp, sp, si}, "manipulation sphere");
    if (!sphere) return sphere.error();
    s_->sphere = sphere.value();
    s_->models[s_->sphere].internal = true;
#ifdef __GLIBC__
    malloc_trim(0);  // the shader compiler's and upload scratch back to the system
#endif
    BODY_GL_CHECK("init");
    return ok_status();
}

namespace {
void free_model(Model& m) {
    GLuint buffers[] = {m.vbo_position, m.vbo_normal, m.ebo, m.vbo_morph};
    glDeleteBuffers(4, buffers);
    glDeleteVertexArrays(1, &m.vao);
    GLuint textures[] = {m.position_texture, m.position_texture_z, m.edge_texture};
    glDeleteTextures(3, textures);
}
}  // namespace

void Renderer::shutdown() {
    for (auto& [id, m] : s_->models) free_model(m);
    s_->models.clear();
    for (Program* p : {&s_->baseline, &s_->smooth, &s_->hatching, &s_->xray, &s_->edges, &s_->wireframe}) {
        if (p->id) glDeleteProgram(p->id);
        *p = Program{};
    }
    if (s_->tam) glDeleteTextures(1, &s_->tam);
    if (s_->wire_vao) glDeleteVertexArrays(1, &s_->wire_vao);
    if (s_->quad_vao) glDeleteVertexArrays(1, &s_->quad_vao);
    if (s_->quad_ebo) glDeleteBuffers(1, &s_->quad_ebo);
    s_->tam = s_->wire_vao = s_->quad_vao = s_->quad_ebo = 0;
    s_->ready = false;
}

Result<ModelId> Renderer::add_model(const MeshData& mesh, const std::string& name) {
    const PositionView pos(mesh);
    // Filled in place (MeshData::index_fill): the source writes the whole buffer.
    const bool filled = mesh.indices.empty() && mesh.index_fill && !mesh.prefix_only &&
                        (!mesh.normals.empty() || !mesh.normal_codes.empty());
    const size_t isize = filled ? mesh.index_fill_count : mesh.indices.size();
    const size_t vcount = mesh.vertex_count == SIZE_MAX ? pos.size() : mesh.vertex_count;
    const size_t icount = mesh.index_count == SIZE_MAX ? isize : mesh.index_count;
    if (!s_->ready) return runtime_error(name + ": renderer not initialised");
    if (pos.empty() || isize == 0 || vcount == 0 || icount < 3) return input_error(name + ": empty mesh");
    if (pos.coded() && !mesh.has_position_box) return input_error(name + ": position codes without their box");
    if (vcount > pos.size() || icount > isize || (!mesh.normals.empty() && mesh.normals.size() < pos.size()) ||
        (!mesh.normal_codes.empty() && mesh.normal_codes.size() / 2 < pos.size()))
        return input_error(name + ": counts exceed the arrays");
    // prefix_only: capacity past the counts may be unwritten (a progressive mesh
    // still streaming); it arrives through update_model.
    const size_t vupload = mesh.prefix_only ? vcount : pos.size();
    const size_t iupload = filled ? 0 : mesh.prefix_only ? icount : mesh.indices.size();
    for (size_t i = 0; i < iupload; ++i)
        if (mesh.indices[i] >= pos.size())
            return input_error(name + ": index " + std::to_string(i) + " refers to vertex " +
                               std::to_string(mesh.indices[i]) + " of " + std::to_string(pos.size()));
    if (pos.size() > static_cast<size_t>(kTextureWidth) * 8192 || isize > static_cast<size_t>(kTextureWidth) * 8192)
        return input_error(name + ": too large for one model");

    Model m;
    m.name = name;
    m.transfers = &s_->transfers;
    m.vertex_capacity = pos.size();
    m.index_capacity = isize;
    m.vertex_count = vcount;
    m.index_count = icount - icount % 3;
    set_bounds(m, pos, vcount);
    // The quantization box: given (a progressive mesh's, which holds every
    // vertex it will have), or that of all the arrays when they are all written.
    if (mesh.has_position_box || !mesh.prefix_only) {
        Aabb box;
        if (mesh.has_position_box) {
            box.extend(Vec3(mesh.position_box_min));
            box.extend(Vec3(mesh.position_box_max));
        } else {
            for (size_t v = 0; v < pos.size(); ++v) box.extend(Vec3(pos[v]));
            if (mesh.morph_sources.size() >= pos.size())
                for (const Vec3f& p : mesh.morph_sources.first(pos.size())) box.extend(Vec3(p));
        }
        m.quantized = !box.empty();
        m.pos_origin = Vec3f(box.min);
        m.pos_scale = Vec3f(box.max - box.min) / 65535.0f;
        if (pos.coded()) m.pos_origin = pos.origin(), m.pos_scale = pos.scale();  // the codes' own box, bit for bit
        if (m.quantized && !inside_position_box(m, pos, 0, vupload)) m.quantized = false;
        if (!m.quantized) m.pos_origin = Vec3f(0.0f), m.pos_scale = Vec3f(1.0f);
    }

    glGenVertexArrays(1, &m.vao);
    glBindVertexArray(m.vao);
    // The indices go up first when they can: a source handing its array over
    // (MeshData::indices_uploaded) frees it as it goes, before the vertex
    // buffers exist (drivers may clear a new buffer's memory at once:
    // llvmpipe does), so the upload's peak holds one full index array, not two
    // plus the vertex buffers. Computed normals need the indices: then last.
    bool fill_failed = false;
    const auto upload_element_buffer = [&] {
        glGenBuffers(1, &m.ebo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.index_capacity * 4), nullptr, GL_DYNAMIC_DRAW);
        if (filled) {
            MappedRange out(*m.transfers, m.ebo, 0, m.index_capacity * 4,
                            GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
            if (out.data()) mesh.index_fill(std::span<uint32_t>(static_cast<uint32_t*>(out.data()), m.index_capacity));
            fill_failed = !out.data() || !out.unmap();
        }
        upload_indices(mesh, 0, iupload, mesh.prefix_only ? nullptr : mesh.indices_uploaded);
    };
    const bool computed_normals = mesh.normals.empty() && mesh.normal_codes.empty();
    if (!computed_normals) upload_element_buffer();
    // Normals before the positions: computed ones are scratch, freed before the
    // other buffers are filled, so the upload's peak is the buffers or the
    // scratch, not both.
    {
        std::vector<Vec3f> computed;
        std::span<const Vec3f> normals = mesh.normals;
        if (computed_normals) {
            computed = area_normals(pos, mesh.indices.first(m.index_count), pos.size());
            normals = computed;
        }
        m.normal_codes = !mesh.normal_codes.empty();
        glGenBuffers(1, &m.vbo_normal);
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo_normal);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.vertex_capacity * m.normal_stride()), nullptr,
                     GL_DYNAMIC_DRAW);
        upload_normals(m, normals, mesh.normal_codes, 0, vupload);
        if (m.normal_codes) {
            glVertexAttribPointer(kNormalCode, 2, GL_UNSIGNED_BYTE, GL_FALSE, 2, nullptr);
            glEnableVertexAttribArray(kNormalCode);
        } else {
            glVertexAttribPointer(kNormal, 4, GL_INT_2_10_10_10_REV, GL_TRUE, 4, nullptr);
            glEnableVertexAttribArray(kNormal);
        }
        release_scratch(computed);
    }
    glGenBuffers(1, &m.vbo_position);
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_position);
    // Buffers at full capacity, filled up to the counts only.
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.vertex_capacity * m.position_stride()), nullptr,
                 GL_DYNAMIC_DRAW);
    upload_positions(m, pos, 0, vupload);
    position_pointer(m, kPosition);
    glEnableVertexAttribArray(kPosition);
    if (mesh.morph_sources.size() >= pos.size() || mesh.morph_at_rest) {
        glGenBuffers(1, &m.vbo_morph);
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.vertex_capacity * m.position_stride()), nullptr,
                     GL_DYNAMIC_DRAW);
        upload_positions(m, mesh.morph_sources.size() >= pos.size() ? PositionView(mesh.morph_sources) : pos, 0,
                         vupload);
        position_pointer(m, kMorph);
        glEnableVertexAttribArray(kMorph);
    }
    if (computed_normals) upload_element_buffer();
    glBindVertexArray(0);
    if (fill_failed) {
        free_model(m);
        return runtime_error(name + ": the index buffer could not be mapped to fill it, or was lost while mapped");
    }
    BODY_GL_CHECK("add_model");

    ModelId id = s_->next_id++;
    s_->models.emplace(id, std::move(m));
    return id;
}

static void set_bounds_from_buffer(Model& m);

namespace {
// A patch moved vertices out of the quantization box: the model's positions
// (and morph sources) go back to floats, [0, count) uploaded again from the
// full arrays (the rest arrives with later dirty ranges).
void to_float_positions(Model& m, const MeshData& mesh, size_t count) {
    m.quantized = false;
    m.pos_origin = Vec3f(0.0f);
    m.pos_scale = Vec3f(1.0f);
    glBindVertexArray(m.vao);
    for (auto [buffer, location] : {std::pair{m.vbo_position, kPosition}, std::pair{m.vbo_morph, kMorph}}) {
        if (!buffer) continue;
        const PositionView src = location == kMorph && mesh.morph_sources.size() >= count
                                     ? PositionView(mesh.morph_sources)
                                     : PositionView(mesh);
        glBindBuffer(GL_ARRAY_BUFFER, buffer);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.vertex_capacity * sizeof(Vec3f)), nullptr,
                     GL_DYNAMIC_DRAW);
        upload_positions(m, src, 0, count);
        position_pointer(m, location);
    }
    glBindVertexArray(0);
    m.wire_stale = m.edges_stale = true;
}

// Writes a source's pending patches into `buffer`'s elements [first, first +
// count) (`per_element` values of T each), mapped with `access` (MappedRange;
// GL_MAP_READ_BIT added for a patch that reads what it changes: reading a
// write-only mapping is undefined). The range is not invalidated, so the
// entries the patch skips keep theirs.
template <typename T>
Status patch_mapped(Transfers& transfers, GLuint buffer, size_t first, size_t count, size_t per_element,
                    GLbitfield access, const std::function<void(std::span<T>, size_t)>& patch,
                    const std::string& what) {
    const size_t bytes = per_element * sizeof(T);
    MappedRange range(transfers, buffer, first * bytes, count * bytes, access);
    if (!range.data()) return runtime_error(what + " could not be mapped for patching");
    patch(std::span<T>(static_cast<T*>(range.data()), count * per_element), first);
    if (!range.unmap()) return runtime_error(what + " was lost by the driver while mapped for patching");
    return ok_status();
}
}  // namespace

Status Renderer::update_model(ModelId id, const MeshData& mesh, const Dirty& dirty) {
    auto it = s_->models.find(id);
    if (it == s_->models.end()) return input_error("update_model: unknown model " + std::to_string(id));
    Model& m = it->second;
    const PositionView pos(mesh);
    // Patched in place (MeshData::index_patch, ::position_patch): the buffers
    // are the arrays.
    const bool patched = mesh.indices.empty() && mesh.index_patch;
    const bool vpatched =
        pos.empty() && mesh.normals.empty() && mesh.normal_codes.empty() && static_cast<bool>(mesh.position_patch);
    const size_t index_size = patched ? m.index_capacity : mesh.indices.size();
    const size_t vertex_size = vpatched ? m.vertex_capacity : pos.size();
    const size_t vcount = mesh.vertex_count == SIZE_MAX ? vertex_size : mesh.vertex_count;
    const size_t icount = mesh.index_count == SIZE_MAX ? index_size : mesh.index_count;
    if (vertex_size > m.vertex_capacity || index_size > m.index_capacity || vcount > vertex_size ||
        icount > index_size || dirty.vertex_end > vertex_size || (pos.coded() && !mesh.has_position_box) ||
        dirty.index_end > index_size || (!mesh.normals.empty() && mesh.normals.size() < dirty.vertex_end) ||
        (!mesh.normal_codes.empty() && mesh.normal_codes.size() / 2 < dirty.vertex_end) ||
        (patched &&
         (mesh.index_patch_end > index_size || (mesh.normals.empty() && mesh.normal_codes.empty() && !vpatched))) ||
        (vpatched && mesh.position_patch_end > m.vertex_capacity))
        return input_error(m.name + ": update exceeds the uploaded capacity");
    if (vpatched && (!m.quantized || m.vbo_morph || !mesh.has_position_box || m.pos_origin != mesh.position_box_min ||
                     m.pos_scale != (mesh.position_box_max - mesh.position_box_min) / 65535.0f))
        return input_error(m.name + ": position patches need the model's positions as codes in their box, no morph");
    if (!patched)
        for (size_t i = dirty.index_begin; i < dirty.index_end; ++i)
            if (mesh.indices[i] >= pos.size())
                return input_error(m.name + ": index " + std::to_string(i) + " out of range");
    const bool vertex_patched = vpatched && mesh.position_patch_begin < mesh.position_patch_end;
    if (vertex_patched) {
        // Codes: 3 x 16 bits a vertex (the buffer's layout, Model::quantized).
        // The patch XORs the moves into the codes there: it reads them.
        Status st = patch_mapped<uint16_t>(*m.transfers, m.vbo_position, mesh.position_patch_begin,
                                           mesh.position_patch_end - mesh.position_patch_begin, 3,
                                           GL_MAP_READ_BIT | GL_MAP_WRITE_BIT, mesh.position_patch,
                                           m.name + ": the position buffer");
        if (!st.ok()) return st;
    } else if (!vpatched && dirty.vertex_begin < dirty.vertex_end) {
        const size_t b = dirty.vertex_begin, n = dirty.vertex_end - dirty.vertex_begin;
        if (m.quantized && !inside_position_box(m, pos, b, b + n))
            to_float_positions(m, mesh, std::max(vcount, dirty.vertex_end));
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo_position);
        upload_positions(m, pos, b, b + n);
        if (m.vbo_morph && mesh.morph_sources.size() >= dirty.vertex_end) {
            glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
            upload_positions(m, PositionView(mesh.morph_sources), b, b + n);
        } else if (m.vbo_morph && mesh.morph_at_rest) {
            glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
            upload_positions(m, pos, b, b + n);
        }
        std::vector<Vec3f> computed;
        if (mesh.normals.empty() && mesh.normal_codes.empty())
            computed = area_normals(pos, mesh.indices.first(icount - icount % 3), pos.size());
        std::span<const Vec3f> normals = mesh.normals.empty() ? std::span<const Vec3f>(computed) : mesh.normals;
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo_normal);
        upload_normals(m, normals, mesh.normal_codes, b, b + n);
        release_scratch(computed);
        set_bounds(m, pos, vcount);
    }
    const bool index_patched = patched && mesh.index_patch_begin < mesh.index_patch_end;
    if (index_patched) {
        Status st = patch_mapped<uint32_t>(*m.transfers, m.ebo, mesh.index_patch_begin,
                                           mesh.index_patch_end - mesh.index_patch_begin, 1, GL_MAP_WRITE_BIT,
                                           mesh.index_patch, m.name + ": the index buffer");
        if (!st.ok()) return st;
    } else if (!patched && dirty.index_begin < dirty.index_end) {
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
        upload_indices(mesh, dirty.index_begin, dirty.index_end);
    }
    // The edge list holds face normals, so any change rebuilds it (lazily, when
    // drawn in `lines`); the wireframe's position texture only follows the vertices.
    if (icount - icount % 3 != m.index_count || dirty.index_begin < dirty.index_end || index_patched ||
        dirty.vertex_begin < dirty.vertex_end || vertex_patched)
        m.edges_stale = true;
    const bool vertices_changed = vcount != m.vertex_count || dirty.vertex_begin < dirty.vertex_end || vertex_patched;
    if (vertices_changed) m.wire_stale = true;
    m.vertex_count = vcount;
    m.index_count = icount - icount % 3;
    if (vpatched && vertices_changed) set_bounds_from_buffer(m);  // no CPU positions to take them from
    BODY_GL_CHECK("update_model");
    return ok_status();
}

Status Renderer::set_morph_sources(ModelId id, size_t begin, std::span<const Vec3f> sources) {
    auto it = s_->models.find(id);
    if (it == s_->models.end()) return input_error("set_morph_sources: unknown model " + std::to_string(id));
    const Model& m = it->second;
    if (!m.vbo_morph || begin + sources.size() > m.vertex_capacity)
        return input_error(m.name + ": morph sources outside the uploaded capacity (or none uploaded)");
    if (sources.empty()) return ok_status();
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
    // Quantized: clamped to the box (a progressive mesh's parents lie in it).
    upload_positions(m, PositionView(sources, begin), begin, begin + sources.size());
    return ok_status();
}

void Renderer::remove_model(ModelId id) {
    auto it = s_->models.find(id);
    if (it == s_->models.end() || it->second.internal) return;
    free_model(it->second);
    s_->models.erase(it);
}

ModelState* Renderer::state(ModelId id) {
    auto it = s_->models.find(id);
    return it == s_->models.end() || it->second.internal ? nullptr : &it->second.state;
}
const ModelState* Renderer::state(ModelId id) const {
    auto it = s_->models.find(id);
    return it == s_->models.end() || it->second.internal ? nullptr : &it->second.state;
}

std::vector<ModelId> Renderer::models() const {
    std::vector<ModelId> out;
    for (const auto& [id, m] : s_->models)
        if (!m.internal) out.push_back(id);
    return out;
}

bool Renderer::bounds(ModelId id, Vec3f& center, float& radius) const {
    auto it = s_->models.find(id);
    if (it == s_->models.end()) return false;
    center = it->second.center;
    radius = it->second.radius;
    return true;
}

namespace {
// World-space bounding sphere of a model (the largest axis scale of the transform).
void world_sphere(const Model& m, Vec3f& c, float& r) {
    const glm::mat4& t = m.state.transform;
    c = Vec3f(t * glm::vec4(m.center, 1.0f));
    float s = std::max({glm::length(Vec3f(t[0])), glm::length(Vec3f(t[1])), glm::length(Vec3f(t[2]))});
    r = m.radius * s;
}
}  // namespace

void Renderer::scene_bounds(Vec3f& center, float& radius) const {
    Aabb box;
    for (const auto& [id, m] : s_->models) {
        if (m.internal || !m.state.visible) continue;
        Vec3f c;
        float r = 0;
        world_sphere(m, c, r);
        box.extend(Vec3(c - Vec3f(r)));
        box.extend(Vec3(c + Vec3f(r)));
    }
    center = box.empty() ? Vec3f(0.0f) : Vec3f((box.min + box.max) * 0.5);
    radius = box.empty() ? 0.0f : static_cast<float>(glm::length(box.max - box.min) * 0.5 / std::sqrt(3.0)) * 1.0f;
    if (!box.empty()) {
        // Tighter than the box diagonal: the farthest model sphere from the center.
        float r = 0;
        for (const auto& [id, m] : s_->models) {
            if (m.internal || !m.state.visible) continue;
            Vec3f c;
            float mr = 0;
            world_sphere(m, c, mr);
            r = std::max(r, glm::length(c - center) + mr);
        }
        radius = r;
    }
}

bool Renderer::scene_box(Vec3f& lo, Vec3f& hi) const {
    Aabb box;
    for (const auto& [id, m] : s_->models) {
        if (m.internal || !m.state.visible) continue;
        for (int i = 0; i < 8; ++i) {
            Vec3f corner(i & 1 ? m.box_max.x : m.box_min.x, i & 2 ? m.box_max.y : m.box_min.y,
                         i & 4 ? m.box_max.z : m.box_min.z);
            box.extend(Vec3(Vec3f(m.state.transform * glm::vec4(corner, 1.0f))));
        }
    }
    lo = Vec3f(box.min);
    hi = Vec3f(box.max);
    return !box.empty();
}

void Renderer::set_group_style(int group, Style style) {
    for (auto& [id, m] : s_->models)
        if (!m.internal && m.state.group == group) m.state.style = style;
}
void Renderer::set_group_visible(int group, bool visible) {
    for (auto& [id, m] : s_->models)
        if (!m.internal && m.state.group == group) m.state.visible = visible;
}

const FrameStats& Renderer::last_frame_stats() const { return s_->stats; }

BufferAccess Renderer::buffer_access() const {
    return s_->transfers.staged ? BufferAccess::Staged : BufferAccess::InPlace;
}
const TransferStats& Renderer::transfer_stats() const { return s_->transfers.stats; }

size_t Renderer::gpu_bytes() const {
    size_t total = 0;
    constexpr size_t w = kTextureWidth;
    for (const auto& [id, m] : s_->models) {
        total += m.vertex_capacity * (m.position_stride() + m.normal_stride()) + m.index_capacity * 4;
        if (m.vbo_morph) total += m.vertex_capacity * m.position_stride();
        if (m.position_texture) total += (m.vertex_capacity + w - 1) / w * w * 6;
        if (m.edge_texture) total += (m.edge_capacity + w - 1) / w * w * sizeof(GpuEdge);
    }
    if (s_->tam) total += 3 * 256 * 256 * 4 * 4 / 3;  // three RGBA8 layers with mip chains
    return total;
}

namespace {

struct Frame {
    glm::mat4 view, projection;
    glm::vec4 view_ray;  // gl_FragCoord -> view ray (lighting.glsl)
    const Lighting* lighting;
    const FrameOptions* options;
};

void set_matrices(Program& p, const Frame& f, const Model& m) {
    glm::mat4 mv = f.view * m.state.transform;
    glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(mv)));
    glUniformMatrix4fv(p.loc("u_model_view"), 1, GL_FALSE, glm::value_ptr(mv));
    glUniformMatrix4fv(p.loc("u_projection"), 1, GL_FALSE, glm::value_ptr(f.projection));
    glUniformMatrix3fv(p.loc("u_normal_matrix"), 1, GL_FALSE, glm::value_ptr(nm));
    glUniform3fv(p.loc("u_pos_origin"), 1, glm::value_ptr(m.pos_origin));
    glUniform3fv(p.loc("u_pos_scale"), 1, glm::value_ptr(m.pos_scale));
    glUniform1i(p.loc("u_normal_codes"), m.normal_codes ? 1 : 0);
    glUniform4fv(p.loc("u_view_ray"), 1, glm::value_ptr(f.view_ray));
    const bool morphing = m.vbo_morph && m.state.morph < 1.0f && m.state.morph_begin < m.vertex_count;
    glUniform1f(p.loc("u_morph"), morphing ? std::max(m.state.morph, 0.0f) : 1.0f);
    glUniform1i(p.loc("u_morph_begin"), morphing ? static_cast<GLint>(m.state.morph_begin) : INT32_MAX);
}

// Directions are normalized here once, not per fragment.
void set_lights(Program& p, const Lighting& l) {
    auto unit = [](Vec3f v) { return glm::length(v) > 0.0f ? glm::normalize(v) : Vec3f(0.0f, 0.0f, 1.0f); };
    const Vec3f key = unit(l.key_dir), fill = unit(l.fill_dir), rim = unit(l.rim_dir);
    glUniform3fv(p.loc("u_key_dir"), 1, glm::value_ptr(key));
    glUniform3fv(p.loc("u_fill_dir"), 1, glm::value_ptr(fill));
    glUniform3fv(p.loc("u_rim_dir"), 1, glm::value_ptr(rim));
    glUniform4f(p.loc("u_light_levels"), l.key, l.fill, l.rim, l.ambient);
    glUniform3fv(p.loc("u_half_dir"), 1, glm::value_ptr(unit(key + Vec3f(0.0f, 0.0f, 1.0f))));
    glUniform3fv(p.loc("u_key_light"), 1, glm::value_ptr(key * l.key));
    glUniform3fv(p.loc("u_fill_light"), 1, glm::value_ptr(fill * l.fill));
    glUniform2f(p.loc("u_spec_rim"), 0.25f * l.key, 0.5f * l.rim);
}

// `wireframe` draws the triangles unindexed, three vertices each, with the
// model's index buffer bound as the integer attribute kWireVertex: vertex i of
// the draw gets index i, i.e. the mesh vertex of that corner, and i % 3 is the
// corner. Issued in chunks, the attribute re-pointed at each chunk's first
// index and gl_VertexID counting from 0 in each: softpipe (Mesa's reference
// driver, the aarch64 cross smoke's) restarts gl_VertexID in the pieces it
// splits long draws into, which drops most of a large model.
constexpr size_t kVertexIdChunk = 3 * 1024;
void draw_wire_chunks(GLuint vao, GLuint index_buffer, size_t vertices) {
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, index_buffer);
    size_t since_flush = 0;
    FlushPacer pacer;
    for (size_t first = 0; first < vertices; first += kVertexIdChunk) {
        glVertexAttribIPointer(kWireVertex, 1, GL_UNSIGNED_INT, sizeof(uint32_t),
                               reinterpret_cast<const void*>(first * sizeof(uint32_t)));
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(std::min(kVertexIdChunk, vertices - first)));
        since_flush += kVertexIdChunk / 3;
        if (g_flush_large_draws && since_flush >= kFlushTriangles) {
            pacer.flush();  // bounds the software rasterizer's bins (see kFlushTriangles)
            since_flush = 0;
        }
    }
}

// Edge rectangles: one triangle per edge (edges.vert), gl_VertexID =
// u_vertex_base + the index, drawn in chunks of kQuadEdges through one shared
// 16-bit index buffer.
void draw_edge_quads(Program& p, GLuint quad_vao, size_t edges) {
    glBindVertexArray(quad_vao);
    const GLint base = p.loc("u_vertex_base");
    size_t since_flush = 0;
    FlushPacer pacer;
    for (size_t first = 0; first < edges; first += kQuadEdges) {
        const size_t n = std::min(kQuadEdges, edges - first);
        glUniform1i(base, static_cast<GLint>(first * 4));
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(n * 3), GL_UNSIGNED_SHORT, nullptr);
        since_flush += n;
        if (g_flush_large_draws && since_flush >= kFlushTriangles) {
            pacer.flush();  // bounds the software rasterizer's bins (see kFlushTriangles)
            since_flush = 0;
        }
    }
}

void draw_triangles(const Model& m) {
    glBindVertexArray(m.vao);
    const size_t chunk = 3 * kFlushTriangles;
    if (!g_flush_large_draws || m.index_count <= chunk) {
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(m.index_count), GL_UNSIGNED_INT, nullptr);
        return;
    }
    FlushPacer pacer;
    for (size_t first = 0; first < m.index_count; first += chunk) {
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(std::min(chunk, m.index_count - first)), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(first * sizeof(uint32_t)));
        pacer.flush();
    }
}

}  // namespace

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

// Object-space box and bounding sphere of the drawn vertices, read from the
// GL positions (a source that keeps none).
static void set_bounds_from_buffer(Model& m) {
    const MappedPositions positions(m);
    if (!positions.ok()) return;  // the bounds stay those of the last upload
    Aabb box;
    for (size_t v = 0; v < positions.size(); ++v) box.extend(Vec3(positions[v]));
    m.center = Vec3f((box.min + box.max) * 0.5);
    m.radius = static_cast<float>(box.extent() * 0.5);
    m.box_min = Vec3f(box.min);
    m.box_max = Vec3f(box.max);
}

// A model is drawn in one style at a time, so it keeps the lazily built data of
// one line style only: building the `lines` edge texture frees the `wireframe`
// position texture and the other way round (a million-triangle model's are
// 6-26 MiB and 3 MiB). Switching back rebuilds them from the GL buffers.
static void free_wire_textures(Model& m) {
    if (!m.position_texture) return;
    GLuint textures[] = {m.position_texture, m.position_texture_z};
    glDeleteTextures(2, textures);
    m.position_texture = m.position_texture_z = 0;
    m.wire_stale = true;
#ifdef __GLIBC__
    malloc_trim(0);  // software drivers keep textures in host memory: hand it back before the other style builds
#endif
}
static void free_edge_texture(Model& m) {
    if (!m.edge_texture) return;
    glDeleteTextures(1, &m.edge_texture);
    m.edge_texture = 0;
    m.edge_capacity = m.edge_count = 0;
    m.edges_stale = true;
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

// The edge texture of the `lines` style, rebuilt when the mesh changed. The
// index and position buffers are mapped for reading (MappedBuffer) and the
// records are streamed: built, converted to GpuEdges and uploaded kEdgeChunk
// at a time, so the transient CPU memory is the edge walk's window scratch
// (about 1 MiB, EdgeStream) and one chunk (plus, on a discrete GPU, the
// driver's host copy of the two buffers).
static void ensure_edges(Model& m) {
    if (!m.edges_stale && m.edge_texture) return;
    static_assert(sizeof(EdgeRecord) == sizeof(GpuEdge));
    free_wire_textures(m);
    // Mapping is per buffer: both stay mapped while the other target binding moves on.
    MappedBuffer<uint32_t> index_map(m, m.ebo, m.index_count);
    const MappedPositions positions(m);
    const std::span<const uint32_t> indices = index_map.data();
    if (indices.size() != m.index_count || !positions.ok()) {
        m.edge_count = 0;  // mapping failed: no lines this time, retried on the next frame
        return;
    }
    // Box of the edge endpoints, i.e. of the non-degenerate faces' corners:
    // vertices the level does not use do not change the codes.
    Aabb box;
    for (size_t f = 0; f + 2 < indices.size(); f += 3) {
        const uint32_t a = indices[f], b = indices[f + 1], c = indices[f + 2];
        if (a == b || b == c || a == c) continue;
        for (uint32_t v : {a, b, c}) box.extend(Vec3(positions[v]));
    }
    m.edge_origin = box.empty() ? Vec3f(0.0f) : Vec3f(box.min);
    const Vec3f extent = box.empty() ? Vec3f(0.0f) : Vec3f(box.max - box.min);
    m.edge_scale = extent / 65535.0f;
    auto code = [&](const Vec3f& p) {
        glm::uvec3 c(0u);
        for (int k = 0; k < 3; ++k)
            if (extent[k] > 0.0f)
                c[k] = static_cast<uint32_t>(
                    std::lround(std::clamp((p[k] - m.edge_origin[k]) / extent[k], 0.0f, 1.0f) * 65535.0f));
        return c;
    };
    auto face_normal = [&](uint32_t a, uint32_t b, uint32_t c) {
        Vec3f n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
        float l = glm::length(n);
        return l > 0.0f ? n / l : Vec3f(0.0f, 0.0f, 1.0f);
    };
    // Edges between coplanar faces can never be drawn: both faces face the eye
    // alike (no silhouette) and the dihedral angle is zero (no crease at any
    // threshold above 0). They are left out, which takes most of a flat or
    // finely subdivided region's edges off the GPU: faces with the same normal
    // code, and faces whose normals differ by no more than the rounding of
    // their corners to the 16-bit position codes can tilt them (a linearly
    // subdivided 1.1M-triangle bunny keeps 262k of its 1.67M edges instead of
    // 722k). A first walk counts the edges kept so that the texture is sized
    // to them.
    struct Coded {
        EdgeRecord e;
        uint32_t n0, n1;
    };
    auto normals_of = [&](const EdgeRecord& e) {
        const Vec3f n0 = face_normal(e.v0, e.v1, e.a);
        const uint32_t c0 = pack_octahedral(n0);
        const uint32_t c1 = pack_octahedral(e.b == kNoVertex ? -n0 : face_normal(e.v1, e.v0, e.b));
        return Coded{e, c0, c1};
    };
    const Vec3f step = m.quantized ? m.pos_scale : Vec3f(0.0f);
    auto drawable = [&](const Coded& c) {
        return c.e.b == kNoVertex ||
               (c.n0 != c.n1 && !coplanar_within_rounding(positions[c.e.v0], positions[c.e.v1], positions[c.e.a],
                                                          positions[c.e.b], step));
    };
    {
        // 1 MiB of walk scratch and 128 KiB of records: they are alive while
        // the texture is filled, the first frame's peak in `lines`.
        EdgeStream stream(indices, size_t{1} << 20);
        constexpr size_t kEdgeChunk = 4 * kTextureWidth;
        std::vector<EdgeRecord> chunk(std::min(kEdgeChunk, std::max<size_t>(stream.count(), 1)));
        size_t kept = 0;
        while (const size_t n = stream.next(chunk))
            for (size_t i = 0; i < n; ++i) kept += drawable(normals_of(chunk[i]));
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
                const Coded c = normals_of(chunk[i]);
                if (!drawable(c)) continue;
                const glm::uvec3 c0 = code(positions[c.e.v0]), c1 = code(positions[c.e.v1]);
                const GpuEdge g{c0.x | (c0.y << 16), c0.z | (c1.x << 16), c1.y | (c1.z << 16), c.n0 | (c.n1 << 16)};
                std::memcpy(&chunk[out++], &g, sizeof(g));
            }
            texture_rows(m.edge_texture, first, first + out, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                         reinterpret_cast<const uint8_t*>(chunk.data()), sizeof(GpuEdge));
            first += out;
        }
    }
    m.edges_stale = false;
#ifdef __GLIBC__
    malloc_trim(0);  // the walk's scratch (tens of MiB for a big model) back to the system
#endif
}

// The `wireframe` position textures, rebuilt (in place) when the vertices
// changed: per vertex its position as 16-bit codes in the box of the drawn
// vertices, x and y in an RG16UI texel and z in an R16UI one (6 bytes; one
// RGB16UI texel is 8 on llvmpipe, which has no 48-bit format). The indices
// need no texture (see draw_wire_chunks). Built in pieces from the mapped
// buffer, so the only scratch is one piece.
static void ensure_wire_positions(Model& m) {
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
    const auto upload = [&](size_t first, size_t n) {
        texture_rows(m.position_texture, first, first + n, GL_RG_INTEGER, GL_UNSIGNED_SHORT,
                     reinterpret_cast<const uint8_t*>(xy.data()), 4);
        texture_rows(m.position_texture_z, first, first + n, GL_RED_INTEGER, GL_UNSIGNED_SHORT,
                     reinterpret_cast<const uint8_t*>(z.data()), 2);
    };
    if (m.quantized) {  // the buffer's codes are the texture's
        m.wire_origin = m.pos_origin;
        m.wire_scale = m.pos_scale;
        for (size_t first = 0; first < positions.size(); first += kPiece) {
            const size_t n = std::min(kPiece, positions.size() - first);
            const uint16_t* c = positions.codes() + first * 3;
            for (size_t i = 0; i < n; ++i) {
                xy[i * 2] = c[i * 3];
                xy[i * 2 + 1] = c[i * 3 + 1];
                z[i] = c[i * 3 + 2];
            }
            upload(first, n);
        }
        m.wire_stale = false;
        return;
    }
    Aabb box;
    for (size_t v = 0; v < positions.size(); ++v) box.extend(Vec3(positions[v]));
    m.wire_origin = box.empty() ? Vec3f(0.0f) : Vec3f(box.min);
    const Vec3f extent = box.empty() ? Vec3f(0.0f) : Vec3f(box.max - box.min);
    m.wire_scale = extent / 65535.0f;
    const auto code = [&](size_t v, int k) {
        return extent[k] > 0.0f
                   ? static_cast<uint16_t>(std::lround(
                         std::clamp((positions[v][k] - m.wire_origin[k]) / extent[k], 0.0f, 1.0f) * 65535.0f))
                   : uint16_t{0};
    };
    for (size_t first = 0; first < positions.size(); first += kPiece) {
        const size_t n = std::min(kPiece, positions.size() - first);
        for (size_t i = 0; i < n; ++i) {
            xy[i * 2] = code(first + i, 0);
            xy[i * 2 + 1] = code(first + i, 1);
            z[i] = code(first + i, 2);
        }
        upload(first, n);
    }
    m.wire_stale = false;
}

void Renderer::render(const Camera& camera, const Lighting& lighting, const FrameOptions& o) {
    State& s = *s_;
    s.stats = FrameStats{};
    glBindFramebuffer(GL_FRAMEBUFFER, o.framebuffer);
    glViewport(0, 0, o.width, o.height);
    glClearColor(o.background.r, o.background.g, o.background.b, 1.0f);
    glClearDepthf(1.0f);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!s.ready || o.width <= 0 || o.height <= 0) return;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glDisable(GL_BLEND);

    Frame f{camera.view(),
            camera.projection(static_cast<float>(o.width) / static_cast<float>(o.height)),
            {},
            &lighting,
            &o};
    // View ray through pixel (x, y): ((2x/w - 1) / P00, (2y/h - 1) / P11, -1) for a symmetric perspective.
    f.view_ray = glm::vec4(2.0f / (static_cast<float>(o.width) * f.projection[0][0]),
                           2.0f / (static_cast<float>(o.height) * f.projection[1][1]), -1.0f / f.projection[0][0],
                           -1.0f / f.projection[1][1]);
    // Drivers compile a program's shaders at its first draw (llvmpipe: LLVM)
    // and free the compiler's scratch into the heap, a few MiB for a textured
    // shader: a frame that drew a program for the first time hands it back.
    bool first_use = false;
    auto use_program = [&first_use](Program& p) {
        glUseProgram(p.id);
        first_use |= !p.drawn;
        p.drawn = true;
    };
    bool any_selected = false;
    for (auto& [id, m] : s.models) any_selected |= !m.internal && m.state.visible && m.state.selected;
    const bool fade_rest = o.xray_unselected && any_selected;

    // A model whose style uses neither the `lines` nor the `wireframe` data
    // texture gives it back before the frame draws (the new style's own first
    // frame would otherwise stack on it): a million-triangle model's is 3-10
    // MiB, rebuilt from the GL buffers (~0.1 s) if the style returns. Selected
    // or faded models keep theirs (their style returns when deselected), and
    // so does the benchmark's baseline. The driver may free the storage only
    // once this frame has unbound it (llvmpipe: the vertex stage's sampler
    // view), so the heap is trimmed again at the end of the frame.
    bool released = false;
    for (auto& [id, m] : s.models) {
        const Style st = m.state.style;
        if (m.internal || st == Style::Lines || st == Style::Wireframe || st == Style::Baseline) continue;
        if (m.edge_texture || m.position_texture) {
            free_edge_texture(m);
            free_wire_textures(m);
            released = true;
        }
    }

    // ---- opaque pass
    std::vector<Model*> transparent;
    for (auto& [id, m] : s.models) {
        if (m.internal || !m.state.visible || m.index_count == 0) continue;
        if (m.state.selected || fade_rest) {
            transparent.push_back(&m);
            continue;
        }
        ++s.stats.models_drawn;
        s.stats.triangles += m.index_count / 3;
        ++s.stats.draw_calls;
        const Vec3f col = m.state.color;
        switch (m.state.style) {
            case Style::Baseline: {
                use_program(s.baseline);
                set_matrices(s.baseline, f, m);
                glUniform4f(s.baseline.loc("u_color"), col.r, col.g, col.b, 1.0f);
                draw_triangles(m);
                break;
            }
            case Style::Smooth: {
                use_program(s.smooth);
                set_matrices(s.smooth, f, m);
                set_lights(s.smooth, lighting);
                glUniform4f(s.smooth.loc("u_color"), col.r, col.g, col.b, 1.0f);
                draw_triangles(m);
                break;
            }
            case Style::Hatching:
            case Style::Hatching2Tone: {
                Program& p = s.hatching;
                use_program(p);
                set_matrices(p, f, m);
                set_lights(p, lighting);
                // Hatch paper tinted lightly by the structure colour.
                Vec3f paper = glm::mix(o.paper, col, 0.25f);
                glUniform4f(p.loc("u_color"), paper.r, paper.g, paper.b, 1.0f);
                if (!s.tam) create_tonal_art_map(s.tam);
                glActiveTexture(GL_TEXTURE0);
                glBindTexture(GL_TEXTURE_2D_ARRAY, s.tam);
                glUniform1i(p.loc("u_tam"), 0);
                glUniform1f(p.loc("u_hatch_scale"), 1.6f / std::max(m.radius, 1e-6f));
                {
                    // The key light in object space: the view direction times the
                    // inverse rotation R^T = cbrt(det M) M^-1 of M = mat3(model-view)
                    // = s R, so that mesh.vert needs no normal matrix for it.
                    const glm::mat3 mv(f.view * m.state.transform);
                    const Vec3f key = glm::inverse(mv) * std::cbrt(glm::determinant(mv)) * lighting.key_dir;
                    glUniform3fv(
                        p.loc("u_hatch_key"), 1,
                        glm::value_ptr(glm::length(key) > 0.0f ? glm::normalize(key) : Vec3f(0.0f, 0.0f, 1.0f)));
                }
                glUniform1i(p.loc("u_two_tone"), m.state.style == Style::Hatching2Tone ? 1 : 0);
                draw_triangles(m);
                break;
            }
            case Style::Lines: {
                use_program(s.baseline);
                set_matrices(s.baseline, f, m);
                glUniform4f(s.baseline.loc("u_color"), o.paper.r, o.paper.g, o.paper.b, 1.0f);
                glEnable(GL_POLYGON_OFFSET_FILL);
                glPolygonOffset(1.0f, 1.0f);
                draw_triangles(m);
                glDisable(GL_POLYGON_OFFSET_FILL);
                ensure_edges(m);
                Program& p = s.edges;
                use_program(p);
                glm::mat4 mvp = f.projection * f.view * m.state.transform;
                Vec3f eye_object = Vec3f(glm::inverse(m.state.transform) * glm::vec4(camera.eye, 1.0f));
                glUniformMatrix4fv(p.loc("u_model_view_projection"), 1, GL_FALSE, glm::value_ptr(mvp));
                glUniform3fv(p.loc("u_eye_object"), 1, glm::value_ptr(eye_object));
                glUniform1f(p.loc("u_cos_crease"), std::cos(glm::radians(o.crease_angle_deg)));
                glUniform2f(p.loc("u_viewport"), static_cast<float>(o.width), static_cast<float>(o.height));
                glUniform1f(p.loc("u_width_px"), o.line_width_px);
                glUniform4f(p.loc("u_color"), o.ink.r, o.ink.g, o.ink.b, 1.0f);
                glUniform3fv(p.loc("u_quant_origin"), 1, glm::value_ptr(m.edge_origin));
                glUniform3fv(p.loc("u_quant_scale"), 1, glm::value_ptr(m.edge_scale));
                glActiveTexture(GL_TEXTURE0);
                glBindTexture(GL_TEXTURE_2D, m.edge_texture);
                glUniform1i(p.loc("u_edges"), 0);
                glDisable(GL_CULL_FACE);
                draw_edge_quads(p, s.quad_vao, m.edge_count);
                glEnable(GL_CULL_FACE);
                s.stats.edges += m.edge_count;
                ++s.stats.draw_calls;
                break;
            }
            case Style::Wireframe: {
                ensure_wire_positions(m);
                Program& p = s.wireframe;
                use_program(p);
                set_matrices(p, f, m);
                set_lights(p, lighting);
                glUniform4f(p.loc("u_color"), col.r, col.g, col.b, 1.0f);
                glUniform1f(p.loc("u_width_px"), o.line_width_px * 0.75f);
                glUniform3fv(p.loc("u_quant_origin"), 1, glm::value_ptr(m.wire_origin));
                glUniform3fv(p.loc("u_quant_scale"), 1, glm::value_ptr(m.wire_scale));
                glActiveTexture(GL_TEXTURE0);
                glBindTexture(GL_TEXTURE_2D, m.position_texture);
                glUniform1i(p.loc("u_positions"), 0);
                glActiveTexture(GL_TEXTURE1);
                glBindTexture(GL_TEXTURE_2D, m.position_texture_z);
                glUniform1i(p.loc("u_positions_z"), 1);
                glActiveTexture(GL_TEXTURE0);
                draw_wire_chunks(s.wire_vao, m.ebo, m.index_count);
                break;
            }
        }
        BODY_GL_CHECK(style_name(m.state.style));
    }

    // ---- the white manipulation sphere of each selected model, opaque, at its
    // centre (seen through the transparent purple)
    if (o.manipulation_sphere && any_selected) {
        Model& sphere = s.models[s.sphere];
        use_program(s.smooth);
        set_lights(s.smooth, lighting);
        glUniform4f(s.smooth.loc("u_color"), 0.95f, 0.95f, 0.95f, 1.0f);
        for (auto& [id, m] : s.models) {
            if (m.internal || !m.state.visible || !m.state.selected) continue;
            Vec3f c;
            float r = 0;
            world_sphere(m, c, r);
            sphere.state.transform = glm::scale(glm::translate(glm::mat4(1.0f), c), Vec3f(r * o.sphere_fraction));
            set_matrices(s.smooth, f, sphere);
            draw_triangles(sphere);
            ++s.stats.draw_calls;
        }
    }

    // ---- transparent pass: back to front by view depth of the bounding sphere
    std::vector<std::pair<float, Model*>> order;
    for (Model* m : transparent) {
        Vec3f c;
        float r = 0;
        world_sphere(*m, c, r);
        order.emplace_back((f.view * glm::vec4(c, 1.0f)).z, m);
    }
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    auto draw_transparent = [&](Model& m, Program& p, Vec3f color, float alpha, bool lit, Vec3f rim) {
        use_program(p);
        set_matrices(p, f, m);
        if (lit) set_lights(p, lighting);
        glUniform4f(p.loc("u_color"), color.r, color.g, color.b, alpha);
        glUniform3fv(p.loc("u_rim_color"), 1, glm::value_ptr(rim));
        // Depth pre-pass: only the nearest layer of this model blends.
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        draw_triangles(m);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthFunc(GL_EQUAL);
        draw_triangles(m);
        glDepthFunc(GL_LEQUAL);
        s.stats.draw_calls += 2;
        s.stats.triangles += m.index_count / 3;
        ++s.stats.models_drawn;
    };
    for (auto& [z, m] : order) {
        if (m->state.selected)
            draw_transparent(*m, s.smooth, o.selection_color, 0.55f, true, Vec3f(0.0f));
        else {
            Vec3f c = glm::mix(m->state.color, Vec3f(0.55f, 0.62f, 0.75f), 0.5f);
            draw_transparent(*m, s.xray, c, 0.10f, false, c * 0.8f);
        }
    }
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    glUseProgram(0);
#ifdef __GLIBC__
    if (first_use || released) malloc_trim(0);
#endif
    BODY_GL_CHECK("render");
}

bool Renderer::read_indices(ModelId id, size_t count,
                            const std::function<void(std::span<const uint32_t>)>& read) const {
    auto it = s_->models.find(id);
    if (it == s_->models.end() || count > it->second.index_capacity) return false;
    if (count == 0) {
        read({});
        return true;
    }
    const MappedBuffer<uint32_t> map(it->second, it->second.ebo, count);
    if (map.data().size() != count) return false;
    read(map.data());
    return true;
}

}  // namespace body::render
