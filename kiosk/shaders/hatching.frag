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

// Triplanar TAM lookup; planes with negligible weight are skipped (the
// weights are sharpened so most fragments read one plane), which needs
// explicit gradients since the branches are not uniform.
vec3 g_weights;
vec3 g_p;
vec4 g_dx, g_dy;   // screen derivatives of (p.yz, p.zx)
vec2 g_dxz, g_dyz;  // screen derivatives of p.xy

float tam(float layer) {
    if (layer < 0.0) return 1.0;
    float s = 0.0;
    if (g_weights.x > 0.02) s += g_weights.x * textureGrad(u_tam, vec3(g_p.yz, layer), g_dx.xy, g_dy.xy).r;
    if (g_weights.y > 0.02) s += g_weights.y * textureGrad(u_tam, vec3(g_p.zx, layer), g_dx.zw, g_dy.zw).r;
    if (g_weights.z > 0.02) s += g_weights.z * textureGrad(u_tam, vec3(g_p.xy, layer), g_dxz, g_dyz).r;
    return s;
}

void main() {
    vec3 n = facing_normal(v_view_normal, v_view_pos);
    float light = u_light_levels.x * max(dot(n, normalize(u_key_dir)), 0.0) + u_light_levels.w;
    light = clamp(light, 0.0, 1.0);
    vec3 w = abs(normalize(v_object_normal));
    w = pow(w, vec3(8.0));
    w *= step(0.02 * (w.x + w.y + w.z), w);  // drop negligible planes, renormalize
    g_weights = w / (w.x + w.y + w.z);
    g_p = v_object_pos * u_hatch_scale;
    vec3 px = dFdx(g_p), py = dFdy(g_p);
    g_dx = vec4(px.yz, px.zx);
    g_dy = vec4(py.yz, py.zx);
    g_dxz = px.xy;
    g_dyz = py.xy;
    float ink;
    if (u_two_tone != 0) {
        float t = smoothstep(0.47, 0.53, light);
        ink = t <= 0.0 ? tam(4.0) : t >= 1.0 ? tam(1.0) : mix(tam(4.0), tam(1.0), t);
    } else {
        float s = (1.0 - light) * 6.0;  // 0: white paper, 6: the darkest tone
        float i = floor(s);
        float f = s - i;
        float lighter = f > 0.99 ? 0.0 : tam(i - 1.0);
        float darker = f < 0.01 ? 0.0 : tam(min(i, 5.0));
        ink = mix(lighter, darker, f);
    }
    o_color = vec4(mix(vec3(0.12, 0.11, 0.10), u_color.rgb, ink), 1.0);
}
