#version 300 es
// `lines`: silhouette, boundary and crease edges as screen-space quads of
// constant pixel width (McGuire & Hughes 2004, without geometry shaders).
// Six vertices per mesh edge, found from gl_VertexID (no instancing, which
// software rasterizers run instance by instance; no vertex attributes): the
// edge record (vertices v0, v1 and the unit normals of its two faces packed
// 10:10:10:2, the second zero on a boundary) comes from an integer texture,
// positions from a float texture. An edge is drawn when
// one face looks at the eye and the other away (Zhang's silhouette test, as
// in the thesis), on boundaries, and where the dihedral angle exceeds the
// crease threshold (Raskar & Cohen); otherwise the quad is moved off screen.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp usampler2D;

uniform sampler2D u_positions;  // RGB32F, u_texture_width texels per row
uniform usampler2D u_edges;     // RGBA32UI: v0, v1, packed n0, packed n1
uniform int u_texture_width;
uniform int u_vertex_base;       // the draw is split in chunks; gl_VertexID counts within one
uniform mat4 u_model_view_projection;
uniform vec3 u_eye_object;       // eye in object space (perspective)
uniform float u_cos_crease;      // cosine of the crease threshold
uniform vec2 u_viewport;         // pixels
uniform float u_width_px;        // silhouette width; creases 0.7 of it

// Signed normalized 10:10:10 (the w bits unused) to a vector, in unsigned
// arithmetic only.
vec3 unpack_normal(uint bits) {
    vec3 v = vec3(uvec3(bits, bits >> 10u, bits >> 20u) & uvec3(1023u));
    v -= step(512.0, v) * 1024.0;
    return max(v / 511.0, vec3(-1.0));
}

vec3 fetch(uint i) {
    int k = int(i);
    return texelFetch(u_positions, ivec2(k % u_texture_width, k / u_texture_width), 0).xyz;
}

void main() {
    int vid = u_vertex_base + gl_VertexID;
    int edge = vid / 6;
    // Corners of the quad's two triangles (0,-) (0,+) (1,-) | (1,-) (0,+) (1,+):
    // x = endpoint 0/1, y = side -1/+1.
    int k = vid - edge * 6;
    vec2 a_corner = vec2(k == 2 || k == 3 || k == 5 ? 1.0 : 0.0, k == 1 || k == 4 || k == 5 ? 1.0 : -1.0);
    uvec4 record = texelFetch(u_edges, ivec2(edge % u_texture_width, edge / u_texture_width), 0);
    vec3 p0 = fetch(record.x);
    vec3 p1 = fetch(record.y);
    vec3 n0 = unpack_normal(record.z);
    vec3 n1 = unpack_normal(record.w);
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
