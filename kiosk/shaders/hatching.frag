#version 300 es
// `hatching`: a tonal art map of 6 nested tones with mipmaps (Praun et al.
// 2001), packed as in the paper into two RGB textures (tones 0-2, 3-5) so one
// lookup per texture yields all six; the per-fragment light level picks the
// weights of the two adjacent tones, white above the lightest (Webb et al.
// 2002). Models carry no texture coordinates, so the map is projected on the
// object-space plane facing the normal most (one plane per fragment keeps it at
// two texture reads; tone is preserved across mip levels, so the coarser
// samples at plane seams keep the right tone). u_two_tone selects the thesis'
// threshold variant after Lake et al. 2000: a light (tone 1) and a dark
// (tone 4) hatch texture switched at N.L = 0.5. Two varyings: the view normal
// is the object normal through u_normal_matrix, the view direction comes from
// gl_FragCoord.
precision highp float;
in vec3 v_object_pos;
in vec3 v_object_normal;
uniform vec4 u_color;
uniform mediump sampler2D u_tam_light;  // tones 0, 1, 2 in r, g, b
uniform mediump sampler2D u_tam_dark;   // tones 3, 4, 5 in r, g, b
uniform float u_hatch_scale;            // texture repeats per object-space unit
uniform int u_two_tone;
uniform mat3 u_normal_matrix;
#include "lighting.glsl"
out vec4 o_color;

void main() {
    vec3 n = facing_normal(u_normal_matrix * v_object_normal, view_ray());
    float light = clamp(u_light_levels.x * max(dot(n, u_key_dir), 0.0) + u_light_levels.w, 0.0, 1.0);
    vec3 a = abs(v_object_normal);
    vec3 p = v_object_pos * u_hatch_scale;
    vec2 uv = a.x >= a.y && a.x >= a.z ? p.yz : (a.y >= a.z ? p.zx : p.xy);
    vec3 lo = texture(u_tam_light, uv).rgb;
    vec3 hi = texture(u_tam_dark, uv).rgb;
    float ink;
    if (u_two_tone != 0) {
        ink = mix(hi.g, lo.g, smoothstep(0.47, 0.53, light));
    } else {
        float s = (1.0 - light) * 6.0;  // 0: white paper .. 6: the darkest tone
        vec3 k_lo = vec3(1.0, 2.0, 3.0), k_hi = vec3(4.0, 5.0, 6.0);
        vec3 w_lo = max(vec3(0.0), 1.0 - abs(s - k_lo));
        vec3 w_hi = max(vec3(0.0), 1.0 - abs(s - k_hi));
        ink = max(0.0, 1.0 - s) + dot(w_lo, lo) + dot(w_hi, hi);
    }
    o_color = vec4(mix(vec3(0.12, 0.11, 0.10), u_color.rgb, ink), 1.0);
}
