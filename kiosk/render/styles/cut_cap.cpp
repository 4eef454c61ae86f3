// The cut plane in the frame: the clipped program variants, where each model
// lies against the plane, and stencil capping (contract in cut_cap.h). GLES
// 3.0 has neither gl_ClipDistance nor geometry shaders, so the clip is a
// fragment discard (kiosk/shaders/clip.glsl) and the cap a stencil-masked
// square of the plane (kiosk/shaders/cap.vert + baseline.frag); see the
// capping technique of Nienhuys and of McReynolds & Blythe, "Advanced
// Graphics Programming Using OpenGL" (2005), section 16.10.
#include "kiosk/render/styles/cut_cap.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "kiosk/render/buffer_access.h"
#include "kiosk/render/draw.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/plane_section.h"
#include "kiosk/render/renderer_state.h"
#include "kiosk/render/section_fan.h"

namespace body::render {
namespace {

constexpr glm::vec4 kKeepAll{0.0f, 0.0f, 0.0f, -1.0f};

// The world plane with a unit normal (a zero normal keeps everything).
glm::vec4 unit_plane(const glm::vec4& plane) {
    const float len = glm::length(glm::vec3(plane));
    return len > 0.0f ? plane / len : kKeepAll;
}

// The cap's colour: `color` lit by the frame's key and fill lights as a flat
// surface facing the eye, or the frame's fixed cap colour.
glm::vec4 cap_color(const Frame& f, Vec3f normal_view, Vec3f color, float alpha) {
    const glm::vec4 fixed = f.options->cut.cap_color;
    if (fixed.a > 0.0f) return fixed;
    const Lighting& l = *f.lighting;
    auto unit = [](Vec3f v) { return glm::length(v) > 0.0f ? glm::normalize(v) : Vec3f(0.0f, 0.0f, 1.0f); };
    const float diffuse = l.ambient + l.key * std::max(glm::dot(normal_view, unit(l.key_dir)), 0.0f) +
                          l.fill * std::max(glm::dot(normal_view, unit(l.fill_dir)), 0.0f);
    return glm::vec4(color * diffuse, alpha);
}

// Counts, per pixel, the model's kept faces along the eye ray, all layers:
// back faces +1, front faces -1 (wrapping), no colour or depth written.
void mark_section(RendererState& s, Frame& f, const Model& m) {
    Program& p = s.programs.baseline;  // the clipped variant while the plane is on
    f.use(p);
    set_matrices(p, f, m);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    draw_triangles(f, m);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

// The square of the plane around the model's bounding sphere, in view space
// (the cap of the triangles' count).
void sphere_square(const Frame& f, const Model& m, Vec3f& center_view, Vec3f& axis_u, Vec3f& axis_v) {
    Vec3f c;
    float r = 0.0f;
    world_sphere(m, c, r);
    const glm::vec4 plane = unit_plane(f.options->cut.plane);
    const Vec3f n(plane);
    const float d = glm::dot(n, c) + plane.w;
    // A little larger than the sphere's disc, so rounding never leaves a counted pixel outside.
    const float half = std::sqrt(std::max(r * r - d * d, 0.0f)) * 1.01f + 1e-6f * (r + 1.0f);
    const Vec3f helper = std::abs(n.x) < 0.9f ? Vec3f(1.0f, 0.0f, 0.0f) : Vec3f(0.0f, 1.0f, 0.0f);
    const Vec3f u = glm::normalize(glm::cross(n, helper)), v = glm::cross(n, u);
    const glm::mat3 rot(f.view);
    center_view = Vec3f(f.view * glm::vec4(c - n * d, 1.0f));
    axis_u = rot * (u * half);
    axis_v = rot * (v * half);
}

// The frame's plane in model `m`'s object space (points map by the
// transform T, so planes by its transpose).
glm::vec4 object_plane(const Frame& f, const Model& m) {
    return glm::transpose(m.state.transform) * unit_plane(f.options->cut.plane);
}

// The section's segments of `m` by the object-space `plane` into
// cut.segments (object space); false when a buffer failed to map.
bool find_segments(CutCapState& cut, const Model& m, const glm::vec4& plane) {
    cut.segments.clear();
    const MappedBuffer<uint32_t> indices(m, m.ebo, m.index_count);
    if (indices.data().size() != m.index_count) return false;
    if (!m.quantized) {
        const MappedBuffer<float> positions(m, m.vbo_position, m.vertex_count * 3);
        if (positions.data().size() != m.vertex_count * 3) return false;
        plane_section(positions.data().data(), 3, m.vertex_count, indices.data().data(), m.index_count, plane,
                      cut.segments, cut.distance);
        return true;
    }
    // Codes q with p = origin + scale * q: the plane in code space, the points back after.
    const MappedBuffer<uint16_t> codes(m, m.vbo_position, m.vertex_count * 3);
    if (codes.data().size() != m.vertex_count * 3) return false;
    const Vec3f n(plane);
    const glm::vec4 code_plane(n * m.pos_scale, glm::dot(n, m.pos_origin) + plane.w);
    plane_section(codes.data().data(), 3, m.vertex_count, indices.data().data(), m.index_count, code_plane,
                  cut.segments, cut.distance);
    for (Vec3f& p : cut.segments) p = m.pos_origin + m.pos_scale * p;
    return true;
}

// The section's even-odd triangles (section_fan.h) into the model's section
// buffer, and the rectangle of the plane around the segments (a little
// larger, so rounding never leaves a flipped pixel out).
void store_section(CutCapState& cut, Model& m, const glm::vec4& plane) {
    const Vec3f n = glm::normalize(Vec3f(plane));
    const Vec3f helper = std::abs(n.x) < 0.9f ? Vec3f(1.0f, 0.0f, 0.0f) : Vec3f(0.0f, 1.0f, 0.0f);
    const Vec3f u = glm::normalize(glm::cross(n, helper)), v = glm::cross(n, u);
    glm::vec2 lo(INFINITY), hi(-INFINITY);
    for (const Vec3f& p : cut.segments) {
        const glm::vec2 at(glm::dot(p, u), glm::dot(p, v));
        lo = glm::min(lo, at);
        hi = glm::max(hi, at);
    }
    cut.fan.clear();
    section_fan(cut.segments, n, u, v, lo, hi, section_fan_cells(cut.segments.size() / 2), cut.fan, cut.fan_scratch);
    m.section_vertices = cut.fan.size();
    if (m.section_vertices == 0) return;
    const glm::vec2 mid = 0.5f * (lo + hi), half = 0.5f * (hi - lo) * 1.01f + 1e-4f * (glm::length(hi - lo) + 1e-3f);
    const float along = glm::dot(cut.segments.front(), n);  // every point is on the plane
    m.section_center = n * along + u * mid.x + v * mid.y;
    m.section_u = u * half.x;
    m.section_v = v * half.y;
    if (!m.section_vbo) glGenBuffers(1, &m.section_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m.section_vbo);
    const size_t bytes = cut.fan.size() * sizeof(Vec3f);
    if (bytes > m.section_vbo_capacity) {
        m.section_vbo_capacity = bytes + bytes / 2;
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.section_vbo_capacity), nullptr, GL_DYNAMIC_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), cut.fan.data());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

// Brings `m`'s section up to the frame's plane and its geometry; false when
// its buffers cannot be read (the cap then counts the triangles instead).
bool update_section(RendererState& s, Model& m, const glm::vec4& plane) {
    CutCapState& cut = s.cut;
    if (m.section_valid && m.section_plane == plane && m.section_version == m.geometry_version) return true;
    m.section_valid = false;
    if (!find_segments(cut, m, plane)) return false;
    store_section(cut, m, plane);
    ++s.stats.cut_sections;
    m.section_valid = true;
    m.section_plane = plane;
    m.section_version = m.geometry_version;
    return true;
}

// The section's fan into the stencil, flipping it per triangle (even-odd):
// non-zero exactly inside the section's outlines, on the plane.
void mark_section_fan(CutCapState& cut, Frame& f, const Model& m) {
    Program& p = cut.section;
    f.use(p);
    const glm::mat4 mv = f.view * m.state.transform;
    glUniformMatrix4fv(p.loc("u_projection"), 1, GL_FALSE, glm::value_ptr(f.projection));
    glUniformMatrix4fv(p.loc("u_model_view"), 1, GL_FALSE, glm::value_ptr(mv));
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INVERT);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glBindVertexArray(cut.section_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m.section_vbo);
    glVertexAttribPointer(kPosition, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
    glEnableVertexAttribArray(kPosition);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m.section_vertices));
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

// The cap where the stencil is set: the section's rectangle (object space) or,
// without a section, the square of the plane around the model's bounding
// sphere; depth-tested, it zeroes the stencil it covers.
void fill_cap(CutCapState& cut, CutVolumeState& volume, Frame& f, Vec3f center_view, Vec3f axis_u, Vec3f axis_v,
              Vec3f color, float alpha) {
    const glm::vec4 plane = unit_plane(f.options->cut.plane);
    Vec3f normal_view = glm::normalize(glm::mat3(f.view) * Vec3f(plane));
    if (glm::dot(normal_view, center_view) > 0.0f) normal_view = -normal_view;  // the side the eye sees
    const glm::vec4 col = cap_color(f, normal_view, color, alpha);
    Program* grey = use_cut_volume(volume, f);  // the source image on the cap, when the bundle has one
    Program& p = grey ? *grey : cut.cap;
    if (!grey) f.use(p);
    glUniformMatrix4fv(p.loc("u_projection"), 1, GL_FALSE, glm::value_ptr(f.projection));
    glUniform3fv(p.loc("u_center"), 1, glm::value_ptr(center_view));
    glUniform3fv(p.loc("u_axis_u"), 1, glm::value_ptr(axis_u));
    glUniform3fv(p.loc("u_axis_v"), 1, glm::value_ptr(axis_v));
    glUniform4fv(p.loc("u_color"), 1, glm::value_ptr(col));
    glStencilFunc(GL_NOTEQUAL, 0, 0xFF);
    glStencilOp(GL_ZERO, GL_ZERO, GL_ZERO);
    glBindVertexArray(cut.cap_vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glEnable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
}

// The clipped program table: clipped as geometry where the driver offers
// clip distances (no fragment of the removed side shaded, early depth tests
// kept), else by clip.glsl's discard.
bool link_clipped(Programs& clipped) {
    constexpr const char* kDistance =
        "#extension GL_EXT_clip_cull_distance : require\n#define BODY_CLIP 1\n#define BODY_CLIP_DISTANCE 1\n";
    if (gl_has_extension("GL_EXT_clip_cull_distance") && link_programs(clipped, kDistance)) {
        for (Program* p : {&clipped.baseline, &clipped.smooth, &clipped.hatching, &clipped.xray, &clipped.lines,
                           &clipped.wireframe, &clipped.wireframe_buffer})
            p->clip_distance = true;
        return true;
    }
    return static_cast<bool>(link_programs(clipped, "#define BODY_CLIP 1\n"));
}

}  // namespace

bool prepare_cut(RendererState& s) {
    CutCapState& cut = s.cut;
    if (cut.tried) return cut.ready;
    cut.tried = true;
    if (!link_clipped(cut.clipped)) return false;
    auto cap = link_shader_pair("cap.vert", "baseline.frag");
    if (!cap) {
        delete_programs(cut.clipped);
        return false;
    }
    auto section = link_shader_pair("section.vert", "baseline.frag");
    if (!section) {
        delete_programs(cut.clipped);
        glDeleteProgram(cap.value().id);
        return false;
    }
    cut.cap = std::move(cap.value());
    cut.section = std::move(section.value());
    glGenVertexArrays(1, &cut.cap_vao);
    glGenVertexArrays(1, &cut.section_vao);
    cut.ready = true;
    return true;
}

void free_cut(CutCapState& cut) {
    delete_programs(cut.clipped);
    if (cut.cap.id) glDeleteProgram(cut.cap.id);
    if (cut.cap_vao) glDeleteVertexArrays(1, &cut.cap_vao);
    if (cut.section.id) glDeleteProgram(cut.section.id);
    if (cut.section_vao) glDeleteVertexArrays(1, &cut.section_vao);
    cut = CutCapState{};
}

CutSide begin_model_cut(Frame& f, const Model& m) {
    f.clip_view = f.clip_object = kKeepAll;
    if (!f.clipping || !m.state.cut) return CutSide::Whole;
    Vec3f c;
    float r = 0.0f;
    world_sphere(m, c, r);
    const glm::vec4 plane = unit_plane(f.options->cut.plane);
    const float d = glm::dot(Vec3f(plane), c) + plane.w;
    if (d >= r) return CutSide::Removed;
    if (d <= -r) return CutSide::Whole;
    // Planes map by the inverse transpose of the point transform.
    f.clip_view = glm::transpose(glm::inverse(f.view)) * plane;
    f.clip_object = object_plane(f, m);
    return CutSide::Cut;
}

void set_clip_uniforms(Program& p, const Frame& f) {
    glUniform4fv(p.loc("u_clip_plane"), 1, glm::value_ptr(f.clip_view));
    glUniform4fv(p.loc("u_clip_ray"), 1, glm::value_ptr(f.view_ray));
    glUniform2f(p.loc("u_clip_depth"), f.projection[2][2], f.projection[3][2]);
    glUniform4fv(p.loc("u_clip_object"), 1, glm::value_ptr(f.clip_object));
}

void draw_cut_cap(RendererState& s, Frame& f, Model& m, Vec3f color, float alpha) {
    if (!f.options->cut.caps) return;
    Vec3f center_view, axis_u, axis_v;
    if (update_section(s, m, object_plane(f, m))) {
        if (m.section_vertices == 0) return;  // the plane crosses the sphere, not the mesh
        mark_section_fan(s.cut, f, m);
        const glm::mat4 mv = f.view * m.state.transform;
        center_view = Vec3f(mv * glm::vec4(m.section_center, 1.0f));
        axis_u = glm::mat3(mv) * m.section_u;
        axis_v = glm::mat3(mv) * m.section_v;
        s.stats.triangles += m.section_vertices / 3 + 2;
    } else {
        mark_section(s, f, m);
        sphere_square(f, m, center_view, axis_u, axis_v);
        s.stats.triangles += m.index_count / 3 + 2;
    }
    fill_cap(s.cut, s.cut_volume, f, center_view, axis_u, axis_v, color, alpha);
    s.stats.draw_calls += 2;
}

}  // namespace body::render

namespace body::render {

void Renderer::warm_up_cut(const Lighting& lighting, const FrameOptions& options) {
    RendererState& s = *s_;
    Model* small = nullptr;
    for (auto& [id, m] : s.models)
        if (!m.internal && m.index_count > 0 && (!small || m.index_count < small->index_count)) small = &m;
    if (!small || !prepare_cut(s)) return;
    std::vector<std::pair<Model*, ModelState>> saved;
    for (auto& [id, m] : s.models) {
        if (m.internal) continue;
        saved.emplace_back(&m, m.state);
        m.state.visible = false;
    }
    Vec3f c;
    float r = 0.0f;
    world_sphere(*small, c, r);
    const View view = View::framing(c, std::max(r, 1e-6f));
    const Vec3f n = glm::normalize(view.eye - c);
    FrameOptions o = options;
    o.cut = CutPlane{};
    o.cut.enabled = true;
    o.cut.plane = glm::vec4(n, -glm::dot(n, c));
    small->state.visible = small->state.cut = true;
    small->state.selected = false;
    for (Style style : kAllStyles) {
        small->state.style = style;
        render(view, lighting, o);
    }
    small->state.selected = true;
    render(view, lighting, o);
    for (auto& [m, state] : saved) m->state = state;
}

}  // namespace body::render
