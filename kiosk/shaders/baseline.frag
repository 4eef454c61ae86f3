#version 300 es
// The benchmark's minimal baseline and the paper fill of the `lines` style: one colour.
precision mediump float;
uniform vec4 u_color;
out vec4 o_color;
#include "clip.glsl"
void main() {
    clip_fragment();
    o_color = u_color;
}
