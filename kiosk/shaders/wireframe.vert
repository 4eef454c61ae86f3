#version 300 es
// `wireframe`: GLES has no polygon mode, so triangles are drawn unindexed
// (3 vertices each) and fetch their index and position from textures; the
// barycentric corner comes from gl_VertexID.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp usampler2D;
uniform sampler2D u_positions;  // RGB32F
uniform usampler2D u_indices;   // R32UI
uniform int u_texture_width;
uniform int u_vertex_base;  // the draw is split in chunks; gl_VertexID counts within one
uniform mat4 u_model_view;
uniform mat4 u_projection;
out vec3 v_barycentric;
out vec3 v_view_pos;

void main() {
    int vid = u_vertex_base + gl_VertexID;
    uint index = texelFetch(u_indices, ivec2(vid % u_texture_width, vid / u_texture_width), 0).r;
    int k = int(index);
    vec3 p = texelFetch(u_positions, ivec2(k % u_texture_width, k / u_texture_width), 0).xyz;
    int corner = vid % 3;
    v_barycentric = vec3(corner == 0, corner == 1, corner == 2);
    vec4 view = u_model_view * vec4(p, 1.0);
    v_view_pos = view.xyz;
    gl_Position = u_projection * view;
}
