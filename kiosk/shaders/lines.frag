#version 300 es
// Ink for the `lines` style edges: the triangle lines.vert draws, trimmed to
// its rectangle (highp: a long edge is hundreds of pixels).
precision mediump float;
uniform vec4 u_color;
in highp vec2 v_rect;
out vec4 o_color;
#include "clip.glsl"
void main() {
    clip_fragment();
    if (v_rect.x > 1.0 || v_rect.y > 1.0) discard;
    o_color = u_color;
}
