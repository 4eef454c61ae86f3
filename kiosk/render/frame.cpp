// One frame (Renderer::render): opaque models in their styles (one draw
// function per style, kiosk/render/styles/), the manipulation spheres of the
// selected ones, then the transparent models (selected, x-ray) back to front.
// Layout after Dear ImGui's imgui_impl_opengl3.cpp RenderDrawData.
#include <GLES3/gl3.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <utility>
#include <vector>

#include "kiosk/render/batch.h"
#include "kiosk/render/cut_volume.h"
#include "kiosk/render/data_textures.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/renderer_state.h"
#include "kiosk/render/styles/styles.h"

namespace body::render {
namespace {

// The draw function of each Style, in the enum's order.
constexpr DrawStyle kDrawStyle[] = {draw_smooth,   draw_wireframe, draw_lines,
                                    draw_hatching, draw_hatching,  draw_baseline};
static_assert(static_cast<size_t>(Style::Smooth) == 0 && static_cast<size_t>(Style::Wireframe) == 1 &&
              static_cast<size_t>(Style::Lines) == 2 && static_cast<size_t>(Style::Hatching) == 3 &&
              static_cast<size_t>(Style::Hatching2Tone) == 4 && static_cast<size_t>(Style::Baseline) == 5 &&
              std::size(kDrawStyle) == 6);

// Clears the target and sets the GL state every style starts from; the frame's
// matrices and the view ray through pixel (x, y): ((2x/w - 1) / P00, (2y/h -
// 1) / P11, -1) for a symmetric perspective.
Frame begin_frame(RendererState& s, const View& camera, const Lighting& lighting, const FrameOptions& o) {
    glBindFramebuffer(GL_FRAMEBUFFER, o.framebuffer);
    glViewport(0, 0, o.width, o.height);
    glClearColor(o.background.r, o.background.g, o.background.b, 1.0f);
    glClearDepthf(1.0f);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (o.cut.enabled) {  // the cut plane's caps count in the stencil (styles/cut_cap.h)
        glStencilMask(0xFF);
        glClearStencil(0);
    }
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | (o.cut.enabled ? GL_STENCIL_BUFFER_BIT : 0));
    Frame f{};
    if (!s.ready || o.width <= 0 || o.height <= 0) return f;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glDisable(GL_BLEND);
    f.view = camera.view();
    f.projection = camera.projection(static_cast<float>(o.width) / static_cast<float>(o.height));
    f.view_ray = glm::vec4(2.0f / (static_cast<float>(o.width) * f.projection[0][0]),
                           2.0f / (static_cast<float>(o.height) * f.projection[1][1]), -1.0f / f.projection[0][0],
                           -1.0f / f.projection[1][1]);
    f.camera = &camera;
    f.lighting = &lighting;
    f.options = &o;
    f.flush_large_draws = s.flush_large_draws;
    f.pacer = &s.pacer;
    f.serial = ++s.frame_serial;
    // Gribb and Hartmann: the planes are the rows of P V added to or taken from its last row.
    const glm::mat4 pv = f.projection * f.view;
    for (int i = 0; i < 6; ++i) {
        const int row = i / 2;
        const float sign = i % 2 ? -1.0f : 1.0f;
        glm::vec4 plane;
        for (int c = 0; c < 4; ++c) plane[c] = pv[c][3] + sign * pv[c][row];
        f.frustum[i] = plane / std::max(glm::length(glm::vec3(plane)), 1e-20f);
    }
    f.pixels_at_unit_distance = 0.5f * static_cast<float>(o.height) * f.projection[1][1];
    return f;
}

// Models below this radius on screen are skipped: they would cover a pixel or
// none, and on a scene of thousands of small structures each still costs a draw.
constexpr float kMinRadiusPixels = 0.5f;

// Whether a model's world bounding sphere reaches into the view and is not
// smaller than kMinRadiusPixels there.
bool on_screen(const Frame& f, const Model& m) {
    Vec3f c;
    float r = 0.0f;
    world_sphere(m, c, r);
    for (const glm::vec4& plane : f.frustum)
        if (glm::dot(glm::vec3(plane), c) + plane.w < -r) return false;
    const float depth = -(f.view * glm::vec4(c, 1.0f)).z;
    return depth <= r || r * f.pixels_at_unit_distance >= kMinRadiusPixels * depth;
}

// A model whose style uses neither the `lines` nor the `wireframe` data
// texture gives it back before the frame draws (the new style's own first
// frame would otherwise stack on it); it is rebuilt from the GL buffers if
// the style returns. Selected or faded models keep theirs (their style
// returns when deselected), and so does the benchmark's baseline. True when
// one was freed.
bool release_unused_line_data(RendererState& s) {
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
    return released;
}

// Draws the opaque models in their styles; returns the transparent ones
// (selected, or faded while something is selected and x-ray is on).
// The models that batched drawing takes (batch.h) are drawn after
// the others, many per call.
std::vector<Model*> draw_opaque(RendererState& s, Frame& f, bool fade_rest) {
    std::vector<Model*> transparent, batched;
    auto draw_one = [&](Model& m, CutSide cut) {
        ++s.stats.models_drawn;
        s.stats.triangles += m.index_count / 3;
        ++s.stats.draw_calls;
        kDrawStyle[static_cast<size_t>(m.state.style)](s, f, m);
        if (cut == CutSide::Cut) draw_cut_cap(s, f, m, m.state.color, 1.0f);
        BODY_GL_CHECK(style_name(m.state.style));
    };
    for (auto& [id, m] : s.models) {
        if (m.internal || !m.state.visible || m.index_count == 0 || !on_screen(f, m)) continue;
        if (s.batches.enabled && batchable(f, m, fade_rest)) {
            batched.push_back(&m);
            continue;
        }
        const CutSide cut = begin_model_cut(f, m);
        if (cut == CutSide::Removed) continue;
        if (m.state.selected || fade_rest) {
            transparent.push_back(&m);
            continue;
        }
        draw_one(m, cut);
    }
    if (!batched.empty())
        for (Model* m : draw_batched(s, f, batched)) draw_one(*m, begin_model_cut(f, *m));
    return transparent;
}

// Back to front by the view depth of each model's bounding sphere.
void draw_transparent(RendererState& s, Frame& f, const std::vector<Model*>& transparent) {
    std::vector<std::pair<float, Model*>> order;
    for (Model* m : transparent) order.emplace_back(view_depth(*m, f.view), m);
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    for (auto& [z, m] : order) {
        const bool cut = begin_model_cut(f, *m) == CutSide::Cut;
        if (m->state.selected)
            draw_selected(s, f, *m);
        else
            draw_xray(s, f, *m);
        if (cut) draw_cut_cap(s, f, *m, m->state.selected ? f.options->selection_color : m->state.color, 0.55f);
    }
    glDisable(GL_BLEND);
}

}  // namespace

void Renderer::render(const View& camera, const Lighting& lighting, const FrameOptions& o) {
    RendererState& s = *s_;
    s.stats = FrameStats{};
    Frame f = begin_frame(s, camera, lighting, o);
    if (!f.options) return;  // nothing to draw (not initialised, or an empty viewport)
    bool any_selected = false;
    for (auto& [id, m] : s.models) any_selected |= !m.internal && m.state.visible && m.state.selected;
    const bool fade_rest = o.xray_unselected && any_selected;
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    bool read_back = false;
    for (auto& [id, m] : s.models)
        if (m.state.visible) refresh_level_order(m, s.level_orders, f.serial, now, s.settle_seconds, read_back);
    s.stats.level_order_ms =
        1e3 * (std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count() - now);
    // The driver may free released storage only once this frame has unbound
    // it (llvmpipe: the vertex stage's sampler view), so the heap is trimmed
    // again at the end of the frame.
    const bool released = release_unused_line_data(s);
    // A cut plane draws with the clipped programs (styles/cut_cap.h) for this frame.
    f.clipping = o.cut.enabled && prepare_cut(s);
    if (f.clipping) std::swap(s.programs, s.cut.clipped);
    const std::vector<Model*> transparent = draw_opaque(s, f, fade_rest);
    if (f.clipping) draw_volume_plane(s, f);           // the source image around the caps, when asked
    f.clip_view = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);  // the spheres are never cut
    f.clip_object = f.clip_view;
    if (o.manipulation_sphere && any_selected) draw_manipulation_spheres(s, f);
    draw_transparent(s, f, transparent);
    if (f.clipping) std::swap(s.programs, s.cut.clipped);
    if (f.clip_distance_on) glDisable(kClipDistance0);  // off for the next frame and the overlay
    glBindVertexArray(0);
    glUseProgram(0);
    s.stats.programs_linked = f.programs_linked;
    // The first frame is the start's clock: its trim waits for the next frame.
    const bool trim = f.first_use || released || s.trim_deferred;
    s.trim_deferred = trim && f.serial == 1;
    if (trim && !s.trim_deferred) trim_heap();
    BODY_GL_CHECK("render");
}

}  // namespace body::render
