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

#include "kiosk/render/draw.h"
#include "kiosk/render/renderer_state.h"

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

// The square of the plane around the model's bounding sphere, where the
// stencil is non-zero, depth-tested; it zeroes the stencil it covers.
void fill_section(RendererState& s, Frame& f, const Model& m, Vec3f color, float alpha) {
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
    const Vec3f center_view = Vec3f(f.view * glm::vec4(c - n * d, 1.0f));
    const Vec3f axis_u = rot * (u * half), axis_v = rot * (v * half);
    Vec3f normal_view = glm::normalize(rot * n);
    if (glm::dot(normal_view, center_view) > 0.0f) normal_view = -normal_view;  // the side the eye sees
    const glm::vec4 col = cap_color(f, normal_view, color, alpha);

    Program& p = s.cut.cap;
    f.use(p);
    glUniformMatrix4fv(p.loc("u_projection"), 1, GL_FALSE, glm::value_ptr(f.projection));
    glUniform3fv(p.loc("u_center"), 1, glm::value_ptr(center_view));
    glUniform3fv(p.loc("u_axis_u"), 1, glm::value_ptr(axis_u));
    glUniform3fv(p.loc("u_axis_v"), 1, glm::value_ptr(axis_v));
    glUniform4fv(p.loc("u_color"), 1, glm::value_ptr(col));
    glStencilFunc(GL_NOTEQUAL, 0, 0xFF);
    glStencilOp(GL_ZERO, GL_ZERO, GL_ZERO);
    glBindVertexArray(s.cut.cap_vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glEnable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
}

}  // namespace

bool prepare_cut(RendererState& s) {
    CutCapState& cut = s.cut;
    if (cut.tried) return cut.ready;
    cut.tried = true;
    if (!link_programs(cut.clipped, "#define BODY_CLIP 1\n")) return false;
    auto cap = link_shader_pair("cap.vert", "baseline.frag");
    if (!cap) {
        delete_programs(cut.clipped);
        return false;
    }
    cut.cap = std::move(cap.value());
    glGenVertexArrays(1, &cut.cap_vao);
    cut.ready = true;
    return true;
}

void free_cut(CutCapState& cut) {
    delete_programs(cut.clipped);
    if (cut.cap.id) glDeleteProgram(cut.cap.id);
    if (cut.cap_vao) glDeleteVertexArrays(1, &cut.cap_vao);
    cut = CutCapState{};
}

CutSide begin_model_cut(Frame& f, const Model& m) {
    f.clip_view = kKeepAll;
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
    return CutSide::Cut;
}

void set_clip_uniforms(Program& p, const Frame& f) {
    glUniform4fv(p.loc("u_clip_plane"), 1, glm::value_ptr(f.clip_view));
    glUniform4fv(p.loc("u_clip_ray"), 1, glm::value_ptr(f.view_ray));
    glUniform2f(p.loc("u_clip_depth"), f.projection[2][2], f.projection[3][2]);
}

void draw_cut_cap(RendererState& s, Frame& f, const Model& m, Vec3f color, float alpha) {
    if (!f.options->cut.caps) return;
    mark_section(s, f, m);
    fill_section(s, f, m, color, alpha);
    s.stats.draw_calls += 2;
    s.stats.triangles += m.index_count / 3 + 2;
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
