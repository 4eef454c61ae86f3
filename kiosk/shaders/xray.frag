#version 300 es
// X-ray/fade for unselected models: transparent, more opaque where the surface
// turns away (Fresnel-like). One varying; the view direction from gl_FragCoord.
precision highp float;
in vec3 v_view_normal;
uniform vec4 u_color;      // rgb, base alpha
uniform vec3 u_rim_color;  // colour toward the outline
#include "lighting.glsl"
#include "clip.glsl"
out vec4 o_color;
void main() {
    clip_fragment();
    vec3 n = normalize(v_view_normal);
    float facing = abs(dot(n, normalize(view_ray())));
    float rim = pow(1.0 - facing, 2.5);
    float a = u_color.a + (1.0 - u_color.a) * rim * 0.85;
    o_color = vec4(mix(u_color.rgb, u_rim_color, rim), a);
}
