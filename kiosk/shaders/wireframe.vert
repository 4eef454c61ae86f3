#version 300 es
// `wireframe`: GLES has no polygon mode, so triangles are drawn unindexed
// (3 vertices each) with the model's index buffer read as the attribute
// a_vertex: each vertex of the draw gets its corner's mesh vertex, whose
// position comes from two textures (16-bit codes in the model's box: x and y
// in RG16UI, z in R16UI, 6 bytes a vertex; llvmpipe pads an RGB16UI texel to
// 8); the barycentric corner is gl_VertexID % 3 (each chunk of the draw starts
// at a triangle). BODY_WIRE_BUFFER: the codes are read from the model's
// position buffer itself, an R16UI buffer texture (3 texels a vertex), so no
// copy of them is made (GLSL ES 3.20, which the program's defines select;
// styles/wireframe.cpp).
precision highp float;
precision highp int;
layout(location = 3) in highp uint a_vertex;
#ifdef BODY_WIRE_BUFFER
precision highp usamplerBuffer;
uniform usamplerBuffer u_position_codes;  // R16UI: x, y, z of vertex k at 3k, 3k + 1, 3k + 2
#else
precision highp usampler2D;
uniform usampler2D u_positions;    // RG16UI: x, y
uniform usampler2D u_positions_z;  // R16UI: z
const int kTextureWidthLog2 = 11;  // texels per row, kiosk/render/data_textures.h's kTextureWidth (shift, not division)
#endif
uniform vec3 u_quant_origin;  // object space of code 0
uniform vec3 u_quant_scale;   // object units per code step
uniform mat4 u_model_view;
uniform mat4 u_projection;
out vec3 v_barycentric;
out vec3 v_view_pos;

#include "clip_vertex.glsl"

void main() {
    int corner = gl_VertexID % 3;
    int k = int(a_vertex);
#ifdef BODY_WIRE_BUFFER
    int first = 3 * k;
    uvec3 code = uvec3(texelFetch(u_position_codes, first).x, texelFetch(u_position_codes, first + 1).x,
                       texelFetch(u_position_codes, first + 2).x);
#else
    ivec2 texel = ivec2(k & ((1 << kTextureWidthLog2) - 1), k >> kTextureWidthLog2);
    uvec3 code = uvec3(texelFetch(u_positions, texel, 0).xy, texelFetch(u_positions_z, texel, 0).x);
#endif
    vec3 p = u_quant_origin + u_quant_scale * vec3(code);
    v_barycentric = vec3(corner == 0, corner == 1, corner == 2);
    vec4 view = u_model_view * vec4(p, 1.0);
    v_view_pos = view.xyz;
    gl_Position = u_projection * view;
    clip_vertex(clip_distance(p));
}
