// Mesh upload: a model's GL buffers created from MeshData (add_model),
// patched with dirty ranges or in place through mapped ranges (update_model,
// set_morph_sources), in the model's position and normal formats (16-bit
// codes in a box or floats; 8:8 octahedral codes or 2_10_10_10), and freed.
// Phases per upload: check the arrays, choose the position format, fill the
// buffers in the order that keeps the upload's peak memory low.
#include <GLES3/gl3.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "kiosk/render/buffer_access.h"
#include "kiosk/render/buffer_growth.h"
#include "kiosk/render/data_textures.h"
#include "kiosk/render/gl_formats.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/programs.h"
#include "kiosk/render/renderer_state.h"

namespace body::render {
namespace {

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
    if (large) trim_heap();
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
                v = decode_normal_code(&codes[(first + i) * 2]);
            }
            if (m.normal_codes)
                encode_normal_code(v, reinterpret_cast<uint8_t*>(piece.data()) + i * 2);
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
                const glm::u16vec3 c = position_code(m.pos_origin, m.pos_scale, src[first + i]);
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

// Object-space box and bounding sphere of the drawn vertices.
void set_bounds(Model& m, const Aabb& box) {
    m.center = Vec3f((box.min + box.max) * 0.5);
    m.radius = static_cast<float>(box.extent() * 0.5);
    m.box_min = Vec3f(box.min);
    m.box_max = Vec3f(box.max);
}
void set_bounds(Model& m, const PositionView& positions, size_t count) {
    Aabb box;
    for (size_t v = 0; v < count; ++v) box.extend(Vec3(positions[v]));
    set_bounds(m, box);
}

// The same, read from the GL positions (a source that keeps none).
void set_bounds_from_buffer(Model& m) {
    const MappedPositions positions(m);
    if (!positions.ok()) return;  // the bounds stay those of the last upload
    Aabb box;
    for (size_t v = 0; v < positions.size(); ++v) box.extend(Vec3(positions[v]));
    set_bounds(m, box);
}

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
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.vertex_allocated * sizeof(Vec3f)), nullptr,
                     GL_DYNAMIC_DRAW);
        upload_positions(m, src, 0, count);
        position_pointer(m, location);
    }
    glBindVertexArray(0);
    m.wire_stale = m.edges_stale = true;
    ++m.geometry_version;
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

// Uploads the positions, morph sources and normals of the vertices [b, e)
// from the full arrays (turning the model's positions to floats when they
// leave its box) and takes the bounds of the vcount drawn vertices.
void upload_dirty_vertices(Model& m, const MeshData& mesh, const PositionView& pos, size_t b, size_t e, size_t vcount,
                           size_t icount) {
    if (m.quantized && !inside_position_box(m, pos, b, e)) to_float_positions(m, mesh, std::max(vcount, e));
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_position);
    upload_positions(m, pos, b, e);
    if (m.vbo_morph && mesh.morph_sources.size() >= e) {
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
        upload_positions(m, PositionView(mesh.morph_sources), b, e);
    } else if (m.vbo_morph && mesh.morph_at_rest) {
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
        upload_positions(m, pos, b, e);
    }
    std::vector<Vec3f> computed;
    if (mesh.normals.empty() && mesh.normal_codes.empty())
        computed = area_normals(pos, mesh.indices.first(icount), pos.size());
    std::span<const Vec3f> normals = mesh.normals.empty() ? std::span<const Vec3f>(computed) : mesh.normals;
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_normal);
    upload_normals(m, normals, mesh.normal_codes, b, e);
    release_scratch(computed);
    set_bounds(m, pos, vcount);
}

// The sizes of one add_model upload.
struct UploadPlan {
    bool filled = false;              // MeshData::index_fill writes the whole element buffer
    size_t isize = 0;                 // entries of the element buffer
    size_t vcount = 0, icount = 0;    // drawn
    size_t vupload = 0, iupload = 0;  // written now
};

// Checks the arrays of an add_model call; errors name `name`.
Result<UploadPlan> plan_upload(const MeshData& mesh, const PositionView& pos, const std::string& name) {
    UploadPlan u;
    // Filled in place (MeshData::index_fill): the source writes the whole buffer.
    u.filled = mesh.indices.empty() && mesh.index_fill && !mesh.prefix_only &&
               (!mesh.normals.empty() || !mesh.normal_codes.empty());
    u.isize = u.filled ? mesh.index_fill_count : mesh.indices.size();
    u.vcount = mesh.vertex_count == SIZE_MAX ? pos.size() : mesh.vertex_count;
    u.icount = mesh.index_count == SIZE_MAX ? u.isize : mesh.index_count;
    if (pos.empty() || u.isize == 0 || u.vcount == 0 || u.icount < 3) return input_error(name + ": empty mesh");
    if (pos.coded() && !mesh.has_position_box) return input_error(name + ": position codes without their box");
    if (u.vcount > pos.size() || u.icount > u.isize || (!mesh.normals.empty() && mesh.normals.size() < pos.size()) ||
        (!mesh.normal_codes.empty() && mesh.normal_codes.size() / 2 < pos.size()))
        return input_error(name + ": counts exceed the arrays");
    // prefix_only: capacity past the counts may be unwritten (a progressive mesh
    // still streaming); it arrives through update_model.
    u.vupload = mesh.prefix_only ? u.vcount : pos.size();
    u.iupload = u.filled ? 0 : mesh.prefix_only ? u.icount : mesh.indices.size();
    for (size_t i = 0; i < u.iupload; ++i)
        if (mesh.indices[i] >= pos.size())
            return input_error(name + ": index " + std::to_string(i) + " refers to vertex " +
                               std::to_string(mesh.indices[i]) + " of " + std::to_string(pos.size()));
    const size_t vertex_capacity = std::max(pos.size(), mesh.prefix_only ? mesh.vertex_capacity : 0);
    const size_t index_capacity = std::max(u.isize, mesh.prefix_only ? mesh.index_capacity : 0);
    if (vertex_capacity > static_cast<size_t>(kTextureWidth) * 8192 ||
        index_capacity > static_cast<size_t>(kTextureWidth) * 8192)
        return input_error(name + ": too large for one model");
    return u;
}

// The quantization box: given (a progressive mesh's, which holds every
// vertex it will have), or that of all the arrays when they are all written;
// else (or when the written positions leave it) floats.
void choose_position_format(Model& m, const MeshData& mesh, const PositionView& pos, size_t vupload) {
    if (!mesh.has_position_box && mesh.prefix_only) return;
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

// The element buffer at full capacity, filled by the source (MeshData::
// index_fill) or with the indices to upload. False when the fill could not
// map the buffer or the driver lost it while mapped.
bool upload_element_buffer(Model& m, const MeshData& mesh, const UploadPlan& u) {
    glGenBuffers(1, &m.ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.index_allocated * 4), nullptr, GL_DYNAMIC_DRAW);
    bool fill_failed = false;
    if (u.filled) {
        MappedRange out(*m.transfers, m.ebo, 0, m.index_capacity * 4, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
        if (out.data()) mesh.index_fill(std::span<uint32_t>(static_cast<uint32_t*>(out.data()), m.index_capacity));
        fill_failed = !out.data() || !out.unmap();
    }
    upload_indices(mesh, 0, u.iupload, mesh.prefix_only ? nullptr : mesh.indices_uploaded);
    return !fill_failed;
}

// The normal buffer in the model's format, from the source's normals or codes,
// or area-weighted normals computed from the indices (scratch, freed before
// the position buffers are filled, so the upload's peak is the buffers or the
// scratch, not both).
void upload_normal_buffer(Model& m, const MeshData& mesh, const PositionView& pos, size_t vupload) {
    std::vector<Vec3f> computed;
    std::span<const Vec3f> normals = mesh.normals;
    if (mesh.normals.empty() && mesh.normal_codes.empty()) {
        computed = area_normals(pos, mesh.indices.first(m.index_count), pos.size());
        normals = computed;
    }
    m.normal_codes = !mesh.normal_codes.empty();
    glGenBuffers(1, &m.vbo_normal);
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_normal);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.vertex_allocated * m.normal_stride()), nullptr,
                 GL_DYNAMIC_DRAW);
    upload_normals(m, normals, mesh.normal_codes, 0, vupload);
    normal_pointer(m);
    release_scratch(computed);
}

// A position (or morph source) buffer at full capacity in the model's format,
// filled with the vertices to upload, as attribute `location`.
GLuint upload_position_buffer(const Model& m, const PositionView& src, size_t vupload, GLuint location) {
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.vertex_allocated * m.position_stride()), nullptr,
                 GL_DYNAMIC_DRAW);
    upload_positions(m, src, 0, vupload);
    position_pointer(m, location);
    glEnableVertexAttribArray(location);
    return buffer;
}

// The model's vertex array and buffers. The indices go up first when they
// can: a source handing its array over (MeshData::indices_uploaded) frees it
// as it goes, before the vertex buffers exist (drivers may clear a new
// buffer's memory at once: llvmpipe does), so the upload's peak holds one full
// index array, not two plus the vertex buffers. Computed normals need the
// indices: then last. False when the index fill failed.
bool upload_buffers(Model& m, const MeshData& mesh, const PositionView& pos, const UploadPlan& u) {
    glGenVertexArrays(1, &m.vao);
    glBindVertexArray(m.vao);
    const bool computed_normals = mesh.normals.empty() && mesh.normal_codes.empty();
    bool index_ok = true;
    if (!computed_normals) index_ok = upload_element_buffer(m, mesh, u);
    upload_normal_buffer(m, mesh, pos, u.vupload);
    m.vbo_position = upload_position_buffer(m, pos, u.vupload, kPosition);
    if (mesh.morph_sources.size() >= pos.size() || mesh.morph_at_rest)
        m.vbo_morph = upload_position_buffer(
            m, mesh.morph_sources.size() >= pos.size() ? PositionView(mesh.morph_sources) : pos, u.vupload, kMorph);
    if (computed_normals) index_ok = upload_element_buffer(m, mesh, u);
    glBindVertexArray(0);
    return index_ok;
}

}  // namespace

Result<ModelId> Renderer::add_model(const MeshData& mesh, const std::string& name) {
    const PositionView pos(mesh);
    if (!s_->ready) return runtime_error(name + ": renderer not initialised");
    auto planned = plan_upload(mesh, pos, name);
    if (!planned) return planned.error();
    const UploadPlan& u = planned.value();
    Model m;
    m.name = name;
    m.transfers = &s_->transfers;
    m.vertex_capacity = std::max(pos.size(), mesh.prefix_only ? mesh.vertex_capacity : 0);
    m.index_capacity = std::max(u.isize, mesh.prefix_only ? mesh.index_capacity : 0);
    // A streaming source's buffers hold what is written; they grow with later updates (buffer_growth.h).
    m.vertex_allocated = std::max<size_t>(u.vupload, 1);
    m.index_allocated = u.filled ? u.isize : std::max<size_t>(u.iupload, 3);
    m.vertex_count = u.vcount;
    m.index_count = u.icount - u.icount % 3;
    m.order.enabled = mesh.order_settled_levels;
    set_bounds(m, pos, u.vcount);
    choose_position_format(m, mesh, pos, u.vupload);
    if (!upload_buffers(m, mesh, pos, u)) {
        free_model(m);
        return runtime_error(name + ": the index buffer could not be mapped to fill it, or was lost while mapped");
    }
    BODY_GL_CHECK("add_model");

    ModelId id = s_->next_id++;
    s_->models.emplace(id, std::move(m));
    return id;
}

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
    // A level ordered in place holds its triangles out of the prefix's order: put back before the indices move.
    const bool index_writes =
        patched ? mesh.index_patch_begin < mesh.index_patch_end : dirty.index_begin < dirty.index_end;
    if ((index_writes || icount - icount % 3 != m.index_count) && !restore_level_prefix(m))
        return runtime_error(m.name + ": the index buffer could not be mapped to restore its level's order");
    reserve_vertices(m, std::max({vcount, dirty.vertex_end, vpatched ? mesh.position_patch_end : 0}));
    reserve_indices(m, std::max({icount, dirty.index_end, patched ? mesh.index_patch_end : 0}));
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
        upload_dirty_vertices(m, mesh, pos, dirty.vertex_begin, dirty.vertex_end, vcount, icount - icount % 3);
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
        dirty.vertex_begin < dirty.vertex_end || vertex_patched) {
        m.edges_stale = true;
        ++m.geometry_version;
    }
    const bool vertices_changed = vcount != m.vertex_count || dirty.vertex_begin < dirty.vertex_end || vertex_patched;
    if (vertices_changed) m.wire_stale = true;
    if (vertices_changed) ++m.geometry_version;
    m.vertex_count = vcount;
    m.index_count = icount - icount % 3;
    if (vpatched && vertices_changed) set_bounds_from_buffer(m);  // no CPU positions to take them from
    BODY_GL_CHECK("update_model");
    return ok_status();
}

Status Renderer::set_morph_sources(ModelId id, size_t begin, std::span<const Vec3f> sources) {
    auto it = s_->models.find(id);
    if (it == s_->models.end()) return input_error("set_morph_sources: unknown model " + std::to_string(id));
    Model& m = it->second;
    if (!m.vbo_morph || begin + sources.size() > m.vertex_capacity)
        return input_error(m.name + ": morph sources outside the uploaded capacity (or none uploaded)");
    if (sources.empty()) return ok_status();
    reserve_vertices(m, begin + sources.size());
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo_morph);
    // Quantized: clamped to the box (a progressive mesh's parents lie in it).
    upload_positions(m, PositionView(sources, begin), begin, begin + sources.size());
    return ok_status();
}

void free_model(Model& m) {
    GLuint buffers[] = {m.vbo_position, m.vbo_normal, m.ebo, m.vbo_morph};
    glDeleteBuffers(4, buffers);
    glDeleteVertexArrays(1, &m.vao);
    GLuint textures[] = {m.position_texture, m.position_texture_z, m.edge_texture, m.position_buffer_texture};
    glDeleteTextures(4, textures);
    if (m.section_vbo) glDeleteBuffers(1, &m.section_vbo);
    free_level_order(m);
}

}  // namespace body::render
