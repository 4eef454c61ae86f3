#version 300 es
// `wireframe`: GLES has no polygon mode, so triangles are drawn unindexed
// (3 vertices each) and fetch their triangle's indices and the corner's
// position from textures; the barycentric corner comes from gl_VertexID.
// Positions are 16-bit codes in the model's box (6 bytes a vertex), a
// triangle's indices 21 bits each in two words (or three words for models with
// more than 2^21 vertices).
precision highp float;
precision highp int;
precision highp usampler2D;
uniform usampler2D u_positions;  // RGB16UI
uniform usampler2D u_indices;    // RG32UI (packed) or RGB32UI, one triangle per texel
uniform bool u_packed_indices;
uniform int u_texture_width;
uniform int u_vertex_base;  // the draw is split in chunks; gl_VertexID counts within one
uniform vec3 u_quant_origin;  // object space of code 0
uniform vec3 u_quant_scale;   // object units per code step
uniform mat4 u_model_view;
uniform mat4 u_projection;
out vec3 v_barycentric;
out vec3 v_view_pos;

void main() {
    int vid = u_vertex_base + gl_VertexID;
    int tri = vid / 3;
    int corner = vid - tri * 3;
    uvec4 t = texelFetch(u_indices, ivec2(tri % u_texture_width, tri / u_texture_width), 0);
    uint index;
    if (u_packed_indices)
        index = corner == 0 ? t.x & 0x1fffffu : corner == 1 ? (t.x >> 21u) | ((t.y & 0x3ffu) << 11u) : t.y >> 10u;
    else
        index = corner == 0 ? t.x : corner == 1 ? t.y : t.z;
    int k = int(index);
    vec3 p = u_quant_origin + u_quant_scale * vec3(texelFetch(u_positions, ivec2(k % u_texture_width, k / u_texture_width), 0).xyz);
    v_barycentric = vec3(corner == 0, corner == 1, corner == 2);
    vec4 view = u_model_view * vec4(p, 1.0);
    v_view_pos = view.xyz;
    gl_Position = u_projection * view;
}
