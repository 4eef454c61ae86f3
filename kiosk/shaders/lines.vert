#version 300 es
// `lines`: silhouette, boundary and crease edges as screen-space rectangles of
// constant pixel width (McGuire & Hughes 2004, without geometry shaders).
// One triangle per mesh edge, twice the rectangle's size, that lines.frag trims
// to the rectangle: its right angle is at one corner of the rectangle and its
// legs are twice the rectangle's sides, so its hypotenuse passes through the
// opposite corner. A quad would take two triangles and four vertices; most
// edges are not drawn, and on a real GPU their primitives and vertices are the
// style's cost, so one triangle each (bench/RESULTS.md).
// Vertices come from gl_VertexID = 4 * edge + corner, corner 0..2 (no
// instancing, which software rasterizers run instance by instance; no vertex
// attributes). One texel per edge (RGBA32UI, 16 bytes) holds all it needs:
// both endpoints quantized to 16 bits in the model's edge box and the unit
// normals of its two faces as 8:8 octahedral codes; a boundary edge carries
// the negated first normal as its second. An edge is drawn when one face looks
// at the eye and the other away (Zhang's silhouette test, as in the thesis), on
// boundaries, and where the dihedral angle exceeds the crease threshold
// (Raskar & Cohen); otherwise its triangle is moved off screen.
precision highp float;
precision highp int;
precision highp usampler2D;

uniform usampler2D u_edges;  // RGBA32UI, one edge per texel
// Texels per row of the edge texture (kTextureWidth = 2^11, kiosk/render/data_textures.h): a
// constant shift and mask, since a division by a uniform is per-lane integer
// division on a software rasterizer.
const int kTextureWidthLog2 = 11;
uniform int u_vertex_base;  // the draw is split in chunks; gl_VertexID counts within one
uniform vec3 u_quant_origin;  // object space of code 0
uniform vec3 u_quant_scale;   // object units per code step
uniform mat4 u_model_view_projection;
uniform vec3 u_eye_object;   // eye in object space (perspective)
uniform float u_cos_crease;  // cosine of the crease threshold
uniform vec2 u_viewport;     // pixels
uniform float u_width_px;    // silhouette width; creases 0.7 of it

#include "normal_code.glsl"
#include "clip_vertex.glsl"

// A face normal as its 8:8 octahedral code, x in the low byte.
vec3 unpack_normal(uint bits) { return oct_decode8(vec2(uvec2(bits, bits >> 8u) & uvec2(255u))); }

out highp vec2 v_rect;  // (1, 1) is the rectangle's far corner; lines.frag discards beyond

void main() {
    int vid = u_vertex_base + gl_VertexID;
    int edge = vid >> 2;
    int k = vid & 3;  // 0: the right angle, 1: along the edge, 2: across it
    uvec4 r = texelFetch(u_edges, ivec2(edge & ((1 << kTextureWidthLog2) - 1), edge >> kTextureWidthLog2), 0);
    const uint lo = 0xffffu;
    vec3 p0 = u_quant_origin + u_quant_scale * vec3(uvec3(r.x & lo, r.x >> 16u, r.y & lo));
    vec3 p1 = u_quant_origin + u_quant_scale * vec3(uvec3(r.y >> 16u, r.z & lo, r.z >> 16u));
    vec3 n0 = unpack_normal(r.w & lo);
    vec3 n1 = unpack_normal(r.w >> 16u);
    vec3 to_eye = u_eye_object - p0;
    bool front0 = dot(n0, to_eye) > 0.0;
    bool front1 = dot(n1, to_eye) > 0.0;
    float n01 = dot(n0, n1);
    bool boundary = n01 < -0.98;
    bool crease = n01 < u_cos_crease;
    bool draw = boundary || front0 != front1 || (crease && (front0 || front1));
    float width = boundary || front0 != front1 ? u_width_px : 0.7 * u_width_px;
    vec4 c0 = u_model_view_projection * vec4(p0, 1.0);
    vec4 c1 = u_model_view_projection * vec4(p1, 1.0);
    v_rect = vec2(0.0);
    clip_vertex(1.0);
    if (!draw || c0.w <= 0.0 || c1.w <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // clipped away
        return;
    }
    // In pixels: the rectangle runs from half a width before s0 to half a
    // width past s1, half a width to each side. Positions are given with w = 1
    // so that v_rect and the depth are linear in screen space, as they are
    // along a quad whose corners share their endpoint's w.
    vec2 half_viewport = 0.5 * u_viewport;
    vec2 s0 = c0.xy / c0.w * half_viewport;
    vec2 s1 = c1.xy / c1.w * half_viewport;
    float z0 = c0.z / c0.w, z1 = c1.z / c1.w;
    vec2 d = s1 - s0;
    float len = length(d);
    d = len > 1e-4 ? d / len : vec2(1.0, 0.0);
    vec2 side = vec2(-d.y, d.x);
    float half_width = 0.5 * width;
    vec2 corner = s0 - (d + side) * half_width;
    float rect_length = len + 2.0 * half_width;
    float along = k == 1 ? 2.0 * rect_length : 0.0;   // twice the rectangle's length
    float across = k == 2 ? 4.0 * half_width : 0.0;  // twice its width
    vec2 s = corner + d * along + side * across;
    // Depth as on the quad: z0 at the rectangle's near end, z1 at its far end,
    // so it stays between them over the rectangle.
    float z = mix(z0, z1, along / rect_length);
    clip_vertex(mix(clip_distance(p0), clip_distance(p1), along / rect_length));  // as the depth
    v_rect = vec2(k == 1 ? 2.0 : 0.0, k == 2 ? 2.0 : 0.0);
    gl_Position = vec4(s / half_viewport, z - 2e-5, 1.0);  // ahead of the fill it outlines
}
