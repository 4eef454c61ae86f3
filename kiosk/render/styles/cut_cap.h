#pragma once
// The cut plane in the frame (FrameOptions::cut, kiosk/render/cut_plane.h):
// while a plane is on, the frame draws with the clipped variant of every
// program (kiosk/shaders/clip.glsl discards the removed side; where the
// driver offers GL_EXT_clip_cull_distance, clip_vertex.glsl clips it off as
// geometry instead, so its fragments are never shaded) and caps each
// cut model by stencil: its triangles without depth test, back faces
// incrementing and front faces decrementing the stencil (wrapping), leave a
// non-zero count exactly where the eye's ray enters the kept solid through the
// plane (for a closed mesh seen from outside it); a square of the plane
// around the model is then coloured where the count is non-zero and clears it
// for the next model, so each cap has its own model's colour and depth.
// The stencil comes from the section itself where the model's buffers can be
// read: the plane's crossing segments (kiosk/render/plane_section.h), found
// on the CPU when the plane or the geometry changed and kept while they stay,
// drawn as triangles that flip the stencil (even-odd, short ones:
// kiosk/render/section_fan.h), and the cap is the
// rectangle of the plane around them: a cut costs its section's segments,
// not the model's triangles. The triangles' count above is the fallback
// (buffers that fail to map).
#include <GLES3/gl3.h>

#include <vector>

#include "kiosk/render/programs.h"
#include "kiosk/render/section_fan.h"
#include "shared/geometry.h"

namespace body::render {

struct RendererState;
struct Frame;
struct Model;

// The renderer's cut-plane objects, made at the first frame with a plane.
struct CutCapState {
    bool tried = false, ready = false;
    Programs clipped;  // the program table with BODY_CLIP defined
    Program cap;       // cap.vert + baseline.frag (unclipped: it is the plane)
    GLuint cap_vao = 0;
    Program section;  // section.vert + baseline.frag: the section's fan into the stencil
    GLuint section_vao = 0;
    std::vector<Vec3f> segments, fan;  // scratch of the section (plane_section.h)
    std::vector<float> distance;
    SectionFanScratch fan_scratch;
};

// Where a model lies against the frame's plane.
enum class CutSide { Whole, Cut, Removed };

// Links the clipped programs and the cap on the first call; false (the frame
// draws uncut) when they failed to link.
bool prepare_cut(RendererState& s);
void free_cut(CutCapState& cut);
// Sets Frame::clip_view for model `m` (no clipping for a model that is whole or
// not cut, ModelState::cut) and says where it lies; Whole when no plane is on.
CutSide begin_model_cut(Frame& f, const Model& m);
// The clip.glsl uniforms of the frame's current plane (Frame::use calls it).
void set_clip_uniforms(Program& p, const Frame& f);
// The stencil pass and cap of a model the plane cuts, in `color`; blended
// when alpha < 1 (the transparent pass).
void draw_cut_cap(RendererState& s, Frame& f, Model& m, Vec3f color, float alpha);

}  // namespace body::render
