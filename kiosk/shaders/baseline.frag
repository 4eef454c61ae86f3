#version 300 es
// The benchmark's minimal baseline and the paper fill of the `lines` style: one colour.
precision mediump float;
#ifdef BODY_BATCH
flat in vec4 v_color;  // mesh.vert: the slot's colour (kiosk/render/batch.h)
#define u_color v_color
#else
uniform vec4 u_color;
#endif
out vec4 o_color;
#include "clip.glsl"
void main() {
    clip_fragment();
    o_color = u_color;
}
