#pragma once
// What every style's draw shares: the frame's matrices and options, program
// use, the uniforms of mesh.vert and lighting.glsl, and draw calls that a
// software rasterizer gets in flushed pieces.
#include <GLES3/gl3.h>

#include <cstddef>
#include <glm/glm.hpp>

#include "kiosk/render/flush_pacer.h"
#include "kiosk/render/model.h"
#include "kiosk/render/programs.h"
#include "kiosk/render/renderer.h"

namespace body::render {

// Software rasterizers (llvmpipe) bin every triangle of a frame before
// rasterizing it and keep that memory: large draws are flushed every
// kFlushTriangles, waiting for the scene before (flush_pacer.h), which bounds the
// bins to two scenes of that size (tilers on real GPUs would pay a tile
// resolve per flush, so only software drivers do it; bench/RESULTS.md).
inline constexpr size_t kFlushTriangles = 4 * 1024;

struct Frame;
inline constexpr GLenum kClipDistance0 = 0x3000;  // GL_CLIP_DISTANCE0_EXT (GL_EXT_clip_cull_distance)
// The cut plane's uniforms (kiosk/render/styles/cut_cap.cpp).
void set_clip_uniforms(Program& p, const Frame& f);

// One frame being drawn (Renderer::render, kiosk/render/frame.cpp).
struct Frame {
    glm::mat4 view, projection;
    glm::vec4 view_ray;  // gl_FragCoord -> view ray (lighting.glsl)
    const View* camera;
    const Lighting* lighting;
    const FrameOptions* options;
    bool flush_large_draws = false;  // RendererState::flush_large_draws
    FlushPacer* pacer = nullptr;     // RendererState::pacer: the flushes of large draws
    uint64_t serial = 0;             // RendererState::frame_serial: this frame's number, from 1
    // The view frustum's planes in world space (inside: dot(xyz, p) + w >= 0,
    // xyz of unit length), and pixels per world unit at view distance 1.
    glm::vec4 frustum[6];
    float pixels_at_unit_distance = 0.0f;
    // Drivers compile a program's shaders at its first draw (llvmpipe: LLVM)
    // and free the compiler's scratch into the heap: a frame that drew a
    // program for the first time trims the heap at its end.
    bool first_use = false;
    size_t programs_linked = 0;  // by use() this frame (FrameStats::programs_linked)
    // The cut plane (styles/cut_cap.h): on for this frame, and the view-space
    // plane of the model being drawn ((0, 0, 0, -1) keeps everything).
    bool clipping = false;
    glm::vec4 clip_view{0.0f, 0.0f, 0.0f, -1.0f};
    glm::vec4 clip_object{0.0f, 0.0f, 0.0f, -1.0f};  // the same plane in the model's object space
    // GL_CLIP_DISTANCE0_EXT is on exactly while a program that writes it is in use.
    bool clip_distance_on = false;
    // Makes `p` current, linking it first when this is its first use
    // (programs.h; a program that cannot be linked draws nothing).
    void use(Program& p) {
        if (!p.id && link_on_first_use(p)) ++programs_linked;
        glUseProgram(p.id);
        if (clipping) set_clip_uniforms(p, *this);
        if (p.clip_distance != clip_distance_on) {
            p.clip_distance ? glEnable(kClipDistance0) : glDisable(kClipDistance0);
            clip_distance_on = p.clip_distance;
        }
        first_use |= !p.drawn;
        p.drawn = true;
    }
};

// mesh.vert's uniforms for model `m`: matrices, position dequantization,
// normal format, view ray and geomorph.
void set_matrices(Program& p, const Frame& f, const Model& m);
// lighting.glsl's uniforms from the frame's lights (once a frame per program);
// directions are normalized here once, not per fragment.
void set_lights(Program& p, const Frame& f);
// Draws the model's triangles with a mesh.vert program in one colour
// (u_color), lit by the frame's lights (lighting.glsl) when `lit`.
void draw_coloured(Frame& f, Program& p, const Model& m, const Vec3f& color, bool lit);
// The model's triangles (its element buffer, index_count entries).
void draw_triangles(const Frame& f, const Model& m);
// Entries [first, first + count) of the element buffer of `vao`, flushed in
// pieces on a software rasterizer (kFlushTriangles).
void draw_element_range(const Frame& f, GLuint vao, size_t first, size_t count);

}  // namespace body::render
