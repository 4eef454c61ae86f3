#version 300 es
// `smooth`: per-pixel Blinn-Phong with a soft key/fill/rim setup; also the
// transparent purple of a selected model (u_color.a < 1). One varying (the
// normal, renormalized per fragment).
// Cost on a software rasterizer: llvmpipe runs the fragment shader on whole
// 4x4 blocks for each small triangle, so on a million-triangle model every
// operation here is paid per triangle. The eye direction is taken as the view
// axis (0, 0, 1) for the specular half vector (a uniform) and the rim term
// (n.z) instead of the ray through the pixel: the highlight moves by at most
// the half field of view toward the image border, where the per-pixel ray
// differs from the axis. Back faces are culled, so no flip toward the eye.
precision highp float;
in vec3 v_view_normal;
#ifdef BODY_BATCH
flat in vec4 v_color;  // mesh.vert: the slot's colour (kiosk/render/batch.h)
#define u_color v_color
#else
uniform vec4 u_color;
#endif
#include "lighting.glsl"
#include "clip.glsl"
out vec4 o_color;

void main() {
    clip_fragment();
    vec3 n = v_view_normal * inversesqrt(dot(v_view_normal, v_view_normal));
    float diffuse = max(dot(n, u_key_light), 0.0) + max(dot(n, u_fill_light), 0.0) + u_light_levels.w;
    // pow(x, 40) by squaring: six multiplies instead of a log2 and an exp2.
    float x = max(dot(n, u_half_dir), 0.0), x2 = x * x, x4 = x2 * x2, x8 = x4 * x4, x16 = x8 * x8, x32 = x16 * x16;
    float f = 1.0 - max(n.z, 0.0);
    // Specular 0.25 key x^40 and rim rim f^3 (0.5 + 0.5 max(n.rim, 0)), their constant factors in u_spec_rim.
    float white = u_spec_rim.x * (x32 * x8) + u_spec_rim.y * (f * f * f) * (1.0 + max(dot(n, u_rim_dir), 0.0));
    // No clamp: a fixed-point colour buffer clamps the output to [0, 1] before
    // blending and storing it (GLES 3.0: blending, conversion to fixed point).
    o_color = vec4(u_color.rgb * diffuse + vec3(white), u_color.a);
}
