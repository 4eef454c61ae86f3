#version 300 es
// `lines`: silhouette, boundary and crease edges as screen-space quads of
// constant pixel width (McGuire & Hughes 2004, without geometry shaders).
// One instance per mesh edge: (v0, v1, a, b) with faces (v0, v1, a) and
// (v1, v0, b); b = 0xffffffff on a boundary. Positions come from a float
// texture so the edge list depends on topology only. An edge is drawn when
// one face looks at the eye and the other away (Zhang's silhouette test, as
// in the thesis), on boundaries, and where the dihedral angle exceeds the
// crease threshold (Raskar & Cohen); otherwise the quad is moved off screen.
precision highp float;
precision highp int;
precision highp sampler2D;
layout(location = 0) in vec2 a_corner;  // x: endpoint 0/1, y: side -1/+1
layout(location = 1) in uvec4 a_edge;

uniform sampler2D u_positions;  // RGB32F, u_texture_width texels per row
uniform int u_texture_width;
uniform mat4 u_model_view_projection;
uniform vec3 u_eye_object;       // eye in object space (perspective)
uniform float u_cos_crease;      // cosine of the crease threshold
uniform vec2 u_viewport;         // pixels
uniform float u_width_px;        // silhouette width; creases 0.7 of it

vec3 fetch(uint i) {
    int k = int(i);
    return texelFetch(u_positions, ivec2(k % u_texture_width, k / u_texture_width), 0).xyz;
}

void main() {
    vec3 p0 = fetch(a_edge.x);
    vec3 p1 = fetch(a_edge.y);
    vec3 pa = fetch(a_edge.z);
    vec3 n0 = cross(p1 - p0, pa - p0);
    bool front0 = dot(n0, u_eye_object - p0) > 0.0;
    bool draw;
    float width = u_width_px;
    if (a_edge.w == 0xffffffffu) {
        draw = true;
    } else {
        vec3 pb = fetch(a_edge.w);
        vec3 n1 = cross(p0 - p1, pb - p1);
        bool front1 = dot(n1, u_eye_object - p0) > 0.0;
        float l = length(n0) * length(n1);
        bool crease = l > 0.0 && dot(n0, n1) < u_cos_crease * l;
        draw = front0 != front1 || (crease && (front0 || front1));
        if (front0 == front1) width *= 0.7;
    }
    vec4 c0 = u_model_view_projection * vec4(p0, 1.0);
    vec4 c1 = u_model_view_projection * vec4(p1, 1.0);
    if (!draw || c0.w <= 0.0 || c1.w <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // clipped away
        return;
    }
    vec2 s0 = c0.xy / c0.w * 0.5 * u_viewport;
    vec2 s1 = c1.xy / c1.w * 0.5 * u_viewport;
    vec2 d = s1 - s0;
    d = dot(d, d) > 1e-8 ? normalize(d) : vec2(1.0, 0.0);
    vec2 side = vec2(-d.y, d.x);
    vec4 c = a_corner.x < 0.5 ? c0 : c1;
    float along = a_corner.x < 0.5 ? -1.0 : 1.0;
    vec2 offset_px = (side * a_corner.y + d * along) * 0.5 * width;
    c.xy += offset_px / (0.5 * u_viewport) * c.w;
    c.z -= 2e-5 * c.w;  // ahead of the fill it outlines
    gl_Position = c;
}
