#version 300 es
// Shared vertex stage for the triangle styles (baseline, smooth, hatching,
// paper fill, selection, x-ray): the view-space normal for lighting and, for
// `hatching`, the object-space position in texture repeats with the key light
// level of the vertex in one vec4; each program keeps only the outputs its
// fragment stage reads (the view direction comes from gl_FragCoord, see
// lighting.glsl).
//
// Geomorph (progressive meshes): vertices with index >= u_morph_begin are drawn
// at mix(a_morph, a_position, u_morph), a_morph being the parent's position
// (pm::ProgressiveMesh::morph_targets()); u_morph = 1 draws every vertex at its
// own position. gl_VertexID is the index value in an indexed draw.
//
// Positions (and morph sources) may arrive as 16-bit codes in the model's box
// (kiosk/render/model.h, Model::quantized): object = u_pos_origin + u_pos_scale * code;
// float positions come with origin 0 and scale 1.
//
// Normals arrive as GL_INT_2_10_10_10_REV (a_normal) or, for sources that keep
// 8:8 octahedral codes (a .bpm), as those two bytes (a_normal_code, 0..255
// each; u_normal_codes = 1), decoded here exactly as pm::oct_decode8 does.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_morph;
layout(location = 4) in vec2 a_normal_code;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
uniform vec3 u_pos_origin;
uniform vec3 u_pos_scale;
uniform float u_morph;     // 0: at the parents .. 1: at their own positions
uniform int u_morph_begin;  // first morphing vertex
uniform bool u_normal_codes;  // the normal comes from a_normal_code
uniform float u_hatch_scale;  // hatching: texture repeats per object-space unit
// hatching: unit, toward the key light, in object space (styles/hatching.cpp): no
// normal matrix per vertex; exact for model-views made of a rotation, a uniform
// scale and a translation (the scene's), normalize(N n) . L = n . R^T L.
uniform vec3 u_hatch_key;
uniform vec4 u_light_levels;  // hatching: key, fill, rim, ambient
#ifdef BODY_BATCH
layout(location = 5) in float a_slot;
uniform vec4 u_slots[BODY_BATCH * 10];
flat out vec4 v_color;
#endif

out vec3 v_view_normal;
// `hatching`: xyz the object position in texture repeats, w the tone
// coordinate of the vertex, 6 (1 - light) for the light level of the key light
// and the ambient (0: white paper .. 6: the darkest tone), interpolated (Praun
// et al. 2001 compute the tone per vertex; one varying with the position, as a
// software rasterizer pays per triangle for every varying).
out vec4 v_hatch;

#include "normal_code.glsl"
#include "clip_vertex.glsl"

void main() {
#ifdef BODY_BATCH
    int s = int(a_slot) * 10;
    mat4 model_view = mat4(u_slots[s], u_slots[s + 1], u_slots[s + 2], u_slots[s + 3]);
    mat3 normal_matrix = mat3(u_slots[s + 4].xyz, u_slots[s + 5].xyz, u_slots[s + 6].xyz);
    vec3 p = u_slots[s + 7].xyz + u_slots[s + 8].xyz * a_position;
    vec3 n = oct_decode8(a_normal_code);
    v_color = u_slots[s + 9];
#else
    mat4 model_view = u_model_view;
    mat3 normal_matrix = u_normal_matrix;
    vec3 p = u_pos_origin + u_pos_scale * (gl_VertexID >= u_morph_begin ? mix(a_morph, a_position, u_morph) : a_position);
    vec3 n = u_normal_codes ? oct_decode8(a_normal_code) : a_normal;  // unit (a_normal: to 10 bits)
#endif
    v_view_normal = normal_matrix * n;
    float key = max(dot(n, u_hatch_key), 0.0);
    v_hatch = vec4(p * u_hatch_scale, 6.0 - 6.0 * clamp(u_light_levels.x * key + u_light_levels.w, 0.0, 1.0));
    gl_Position = u_projection * (model_view * vec4(p, 1.0));
    clip_vertex(clip_distance(p));
}
