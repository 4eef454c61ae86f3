#version 300 es
// `hatching`: a tonal art map (6 nested tones, mipmapped; Praun et al. 2001)
// blended per fragment by the key light (Webb et al. 2002: the two adjacent
// tones, white above the lightest), sampled triplanar in object space since
// the models carry no texture coordinates. u_two_tone selects the thesis'
// threshold variant after Lake et al. 2000: a light and a dark hatch texture
// switched at N.L = 0.5.
precision highp float;
precision mediump sampler2DArray;
in vec3 v_view_pos;
in vec3 v_view_normal;
in vec3 v_object_pos;
in vec3 v_object_normal;
uniform vec4 u_color;
uniform sampler2DArray u_tam;
uniform float u_hatch_scale;  // texture repeats per object-space unit
uniform int u_two_tone;
#include "lighting.glsl"
out vec4 o_color;

float tam(vec3 w, vec3 p, float layer) {
    if (layer < 0.0) return 1.0;
    return w.x * texture(u_tam, vec3(p.yz, layer)).r + w.y * texture(u_tam, vec3(p.zx, layer)).r +
           w.z * texture(u_tam, vec3(p.xy, layer)).r;
}

void main() {
    vec3 n = facing_normal(v_view_normal, v_view_pos);
    float light = u_light_levels.x * max(dot(n, normalize(u_key_dir)), 0.0) + u_light_levels.w;
    light = clamp(light, 0.0, 1.0);
    vec3 w = abs(normalize(v_object_normal));
    w = pow(w, vec3(4.0));
    w /= (w.x + w.y + w.z);
    vec3 p = v_object_pos * u_hatch_scale;
    float ink;
    if (u_two_tone != 0) {
        float t = smoothstep(0.47, 0.53, light);
        ink = mix(tam(w, p, 4.0), tam(w, p, 1.0), t);
    } else {
        float s = (1.0 - light) * 6.0;  // 0: white paper, 6: the darkest tone
        float i = floor(s);
        float f = s - i;
        ink = mix(tam(w, p, i - 1.0), tam(w, p, min(i, 5.0)), f);
    }
    o_color = vec4(mix(vec3(0.12, 0.11, 0.10), u_color.rgb, ink), 1.0);
}
