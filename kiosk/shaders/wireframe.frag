#version 300 es
// `wireframe`: edges from the barycentric distance in pixels (fwidth), so the
// line width is constant on screen; faces lightly flat-shaded underneath.
precision highp float;
in vec3 v_barycentric;
in vec3 v_view_pos;
uniform vec4 u_color;
uniform float u_width_px;
#include "lighting.glsl"
#include "clip.glsl"
out vec4 o_color;

void main() {
    vec3 n = normalize(cross(dFdx(v_view_pos), dFdy(v_view_pos)));
    float light = 0.55 + 0.45 * abs(dot(n, u_key_dir));
    vec3 d = v_barycentric / max(fwidth(v_barycentric), vec3(1e-6));
    float px = min(min(d.x, d.y), d.z);
    float edge = 1.0 - smoothstep(0.5 * u_width_px - 0.5, 0.5 * u_width_px + 0.5, px);
    vec3 fill = mix(vec3(1.0), u_color.rgb, 0.35) * light;
    clip_fragment();  // after the derivatives, which need every fragment of the quad
    o_color = vec4(mix(fill, u_color.rgb * 0.35, edge), 1.0);
}
