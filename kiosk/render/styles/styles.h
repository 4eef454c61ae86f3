#pragma once
// One draw function per style, one file each in kiosk/render/styles/ next to
// the shaders of the same name in kiosk/shaders/: smooth, wireframe, lines,
// hatching (both variants), baseline; transparent.cpp draws the selection and
// x-ray passes. An opaque style draws one visible model whose triangles the
// frame (kiosk/render/frame.cpp) has counted already; the context is current.
#include "kiosk/render/draw.h"
#include "kiosk/render/renderer_state.h"

namespace body::render {

using DrawStyle = void (*)(RendererState& s, Frame& f, Model& m);

void draw_smooth(RendererState& s, Frame& f, Model& m);     // mesh.vert + smooth.frag
void draw_wireframe(RendererState& s, Frame& f, Model& m);  // wireframe.vert + wireframe.frag
void draw_lines(RendererState& s, Frame& f, Model& m);      // mesh.vert + baseline.frag, lines.vert + lines.frag
void draw_hatching(RendererState& s, Frame& f, Model& m);   // mesh.vert + hatching.frag (Hatching, Hatching2Tone)
void draw_baseline(RendererState& s, Frame& f, Model& m);   // mesh.vert + baseline.frag

// The shared vertex arrays of the line styles, made once at init (deleted by
// Renderer::shutdown): `lines`' edge-quad index buffer, `wireframe`'s array
// reading a model's index buffer as a vertex attribute.
void create_edge_quads(RendererState& s);
void create_wire_vertex_array(RendererState& s,
                              bool buffer_texture);  // buffer_texture: RendererOptions::wire_buffer_texture

// Transparent pass (transparent.cpp): a selected model in the selection colour
// (mesh.vert + smooth.frag), an unselected one faded by x-ray (xray.frag);
// each with a depth pre-pass so that only its nearest layer blends.
void draw_selected(RendererState& s, Frame& f, Model& m);
void draw_xray(RendererState& s, Frame& f, Model& m);
// The white manipulation sphere at the centre of each visible selected model,
// opaque (seen through the selection colour).
void draw_manipulation_spheres(RendererState& s, Frame& f);

}  // namespace body::render
