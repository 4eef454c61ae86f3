#version 300 es
// `lines`: silhouette, boundary and crease edges as screen-space quads of
// constant pixel width (McGuire & Hughes 2004, without geometry shaders).
// One instance per mesh edge: its vertices v0, v1 (positions fetched from a
// float texture) and the unit normals of its two faces (packed 10:10:10:2,
// the second zero on a boundary), precomputed when the edge list is built
// so each quad corner needs two fetches and no cross products. An edge is drawn when
// one face looks at the eye and the other away (Zhang's silhouette test, as
// in the thesis), on boundaries, and where the dihedral angle exceeds the
// crease threshold (Raskar & Cohen); otherwise the quad is moved off screen.
precision highp float;
precision highp int;
precision highp sampler2D;
layout(location = 0) in vec2 a_corner;  // x: endpoint 0/1, y: side -1/+1
layout(location = 1) in uvec2 a_vertices;
layout(location = 2) in vec4 a_normal0;  // normalized 2_10_10_10
layout(location = 3) in vec4 a_normal1;

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
    vec3 p0 = fetch(a_vertices.x);
    vec3 p1 = fetch(a_vertices.y);
    vec3 n0 = a_normal0.xyz;
    vec3 n1 = a_normal1.xyz;
    vec3 to_eye = u_eye_object - p0;
    bool front0 = dot(n0, to_eye) > 0.0;
    bool draw;
    float width = u_width_px;
    if (dot(n1, n1) < 0.25) {
        draw = true;  // boundary
    } else {
        bool front1 = dot(n1, to_eye) > 0.0;
        bool crease = dot(n0, n1) < u_cos_crease;
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
