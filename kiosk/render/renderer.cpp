// BodyView's GLES 3.0 renderer: init and shutdown around the one state
// struct (renderer_state.h), the model table and what it answers, and the
// style and buffer-access names. Layout after Dear ImGui's
// imgui_impl_opengl3.cpp. Where the rest lives: programs.cpp (shaders),
// buffer_access.cpp (mapping GL buffers), mesh_upload.cpp (add_model,
// update_model), frame.cpp (render), styles/<style>.cpp (each style's draw
// and data).
#include "kiosk/render/renderer.h"

#include <GLES3/gl3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/constants.hpp>
#include <initializer_list>
#include <vector>

#include "kiosk/render/data_textures.h"
#include "kiosk/render/edge_list.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/renderer_state.h"
#include "kiosk/render/styles/styles.h"

namespace body::render {

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

namespace {

// The manipulation sphere: a UV sphere of radius 1.
void make_unit_sphere(std::vector<Vec3f>& positions, std::vector<uint32_t>& indices) {
    const int rings = 24, segments = 48;
    for (int r = 0; r <= rings; ++r)
        for (int g = 0; g <= segments; ++g) {
            float th = glm::pi<float>() * static_cast<float>(r) / rings;
            float ph = 2.0f * glm::pi<float>() * static_cast<float>(g) / segments;
            positions.emplace_back(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
        }
    for (int r = 0; r < rings; ++r)
        for (int g = 0; g < segments; ++g) {
            uint32_t a = static_cast<uint32_t>(r * (segments + 1) + g), b = a + segments + 1;
            indices.insert(indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
}

bool contains(const char* text, std::initializer_list<const char*> words) {
    for (const char* w : words)
        if (text && std::strstr(text, w)) return true;
    return false;
}

}  // namespace

Renderer::Renderer() : s_(std::make_unique<RendererState>()) {}
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
    // Fixing that threshold also fixes the heap's trim threshold at 128 KiB, so
    // llvmpipe's scene blocks (64 KiB, freed at each flush) grew and shrank the
    // heap several times a frame, every page faulted in and zeroed again; twice
    // the mmap threshold is the ratio glibc keeps when it adjusts both itself.
    mallopt(M_TRIM_THRESHOLD, 2 << 20);
#endif
    defer_programs(s_->programs);  // linked as a frame first draws each (the first frame: its styles only)
    if (Status batched = init_batches(s_->batches, options.batch); !batched) {
        shutdown();
        return batched;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    create_wire_vertex_array(*s_, options.wire_buffer_texture);
    create_edge_quads(*s_);
    const char* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    s_->flush_large_draws = contains(gl_renderer, {"llvmpipe", "softpipe"});
    const char* gl_vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    const bool own_memory = contains(gl_vendor, {"NVIDIA", "AMD", "ATI Technologies"});
    s_->transfers.staged =
        options.buffer_access == BufferAccess::Staged || (options.buffer_access == BufferAccess::Auto && own_memory);
    s_->transfers.stats = {};
    s_->settle_seconds = options.settle_seconds;
    if (s_->settle_seconds >= 0.0) s_->level_orders.start();
    s_->ready = true;

    std::vector<Vec3f> sp;
    std::vector<uint32_t> si;
    make_unit_sphere(sp, si);
    auto sphere = add_model({sp, sp, si}, "manipulation sphere");
    if (!sphere) return sphere.error();
    s_->sphere = sphere.value();
    s_->models[s_->sphere].internal = true;
    trim_heap();  // the shader compiler's and upload scratch back to the system
    BODY_GL_CHECK("init");
    return ok_status();
}

void Renderer::shutdown() {
    s_->pacer.release();
    s_->level_orders.stop();
    for (auto& [id, m] : s_->models) free_model(m);
    s_->models.clear();
    shutdown_batches(s_->batches);
    delete_programs(s_->programs);
    free_cut(s_->cut);
    free_cut_volume(s_->cut_volume);
    if (s_->tam) glDeleteTextures(1, &s_->tam);
    if (s_->wire_vao) glDeleteVertexArrays(1, &s_->wire_vao);
    if (s_->quad_vao) glDeleteVertexArrays(1, &s_->quad_vao);
    if (s_->quad_ebo) glDeleteBuffers(1, &s_->quad_ebo);
    s_->tam = s_->wire_vao = s_->quad_vao = s_->quad_ebo = 0;
    s_->ready = false;
}

void Renderer::remove_model(ModelId id) {
    auto it = s_->models.find(id);
    if (it == s_->models.end() || it->second.internal) return;
    forget_batched(*s_, it->second);
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

void world_sphere(const Model& m, Vec3f& c, float& r) {
    const glm::mat4& t = m.state.transform;
    c = Vec3f(t * glm::vec4(m.center, 1.0f));
    float s = std::max({glm::length(Vec3f(t[0])), glm::length(Vec3f(t[1])), glm::length(Vec3f(t[2]))});
    r = m.radius * s;
}

float view_depth(const Model& m, const glm::mat4& view) {
    Vec3f c;
    float r = 0.0f;
    world_sphere(m, c, r);
    return -(view * glm::vec4(c, 1.0f)).z;
}

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

const FrameStats& Renderer::last_frame_stats() const { return s_->stats; }

BufferAccess Renderer::buffer_access() const {
    return s_->transfers.staged ? BufferAccess::Staged : BufferAccess::InPlace;
}
const TransferStats& Renderer::transfer_stats() const { return s_->transfers.stats; }

size_t Renderer::gpu_bytes() const {
    size_t total = 0;
    constexpr size_t w = kTextureWidth;
    for (const auto& [id, m] : s_->models) {
        total += m.vertex_allocated * (m.position_stride() + m.normal_stride()) + m.index_allocated * 4;
        if (m.vbo_morph) total += m.vertex_allocated * m.position_stride();
        if (m.position_texture) total += (m.vertex_capacity + w - 1) / w * w * 6;
        if (m.edge_texture) total += (m.edge_capacity + w - 1) / w * w * sizeof(GpuEdge);
        if (m.order.ebo) total += m.order.count * 4;
    }
    if (s_->tam) total += 3 * 256 * 256 * 4 * 4 / 3;  // three RGBA8 layers with mip chains
    total += s_->cut_volume.bytes;
    return total + batch_gpu_bytes(s_->batches);
}

bool Renderer::read_indices(ModelId id, size_t count,
                            const std::function<void(std::span<const uint32_t>)>& read) const {
    auto it = s_->models.find(id);
    if (it == s_->models.end() || count > it->second.index_allocated) return false;
    if (count == 0) {
        read({});
        return true;
    }
    const MappedBuffer<uint32_t> map(it->second, it->second.ebo, count);
    if (map.data().size() != count) return false;
    read(map.data());
    return true;
}

bool Renderer::level_ordered(ModelId id) const {
    auto it = s_->models.find(id);
    return it != s_->models.end() && render::level_ordered(it->second);
}

bool Renderer::orders_level(ModelId id) const {
    auto it = s_->models.find(id);
    return it != s_->models.end() && render::orders_level(it->second, s_->settle_seconds);
}

void Renderer::finish_level_orders() {
    for (auto& [id, m] : s_->models)
        if (m.order.job) s_->level_orders.wait(*m.order.job);
}

size_t Renderer::level_order_bytes() const {
    size_t total = 0;
    for (const auto& [id, m] : s_->models) total += render::level_order_bytes(m);
    return total;
}

bool Renderer::read_ordered_indices(ModelId id, const std::function<void(std::span<const uint32_t>)>& read) const {
    auto it = s_->models.find(id);
    if (it == s_->models.end() || !render::level_ordered(it->second)) return false;
    const Model& m = it->second;
    const MappedBuffer<uint32_t> map(m, drawn_element_buffer(m), m.index_count);
    if (map.data().size() != m.index_count) return false;
    read(map.data());
    return true;
}

bool Renderer::read_positions(ModelId id, std::vector<Vec3f>& out) const {
    out.clear();
    auto it = s_->models.find(id);
    if (it == s_->models.end()) return false;
    if (it->second.vertex_count == 0) return true;
    const MappedPositions map(it->second);
    if (!map.ok()) return false;
    out.resize(map.size());
    for (size_t v = 0; v < out.size(); ++v) out[v] = map[v];
    return true;
}

}  // namespace body::render
