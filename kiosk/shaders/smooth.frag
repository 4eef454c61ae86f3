#version 300 es
// `smooth`: per-pixel Blinn-Phong with a soft key/fill/rim setup; also the
// transparent purple of a selected model (u_color.a < 1). One varying (the
// normal); the view direction comes from gl_FragCoord.
precision highp float;
in vec3 v_view_normal;
uniform vec4 u_color;
#include "lighting.glsl"
out vec4 o_color;

void main() {
    vec3 ray = view_ray();
    vec3 n = facing_normal(v_view_normal, ray);
    vec3 v = -ray * inversesqrt(dot(ray, ray));
    float diffuse = u_light_levels.x * max(dot(n, u_key_dir), 0.0) + u_light_levels.y * max(dot(n, u_fill_dir), 0.0) +
                    u_light_levels.w;
    vec3 h = normalize(u_key_dir + v);
    // pow(x, 40) by squaring: six multiplies instead of a log2 and an exp2.
    float x = max(dot(n, h), 0.0), x2 = x * x, x4 = x2 * x2, x8 = x4 * x4, x32 = x8 * x8 * x8 * x8;
    float specular = 0.25 * u_light_levels.x * x32 * x8;
    float f = 1.0 - max(dot(n, v), 0.0);
    float rim = u_light_levels.z * f * f * f * (0.5 + 0.5 * max(dot(n, u_rim_dir), 0.0));
    vec3 c = u_color.rgb * diffuse + vec3(specular + rim);
    o_color = vec4(min(c, vec3(1.0)), u_color.a);
}
