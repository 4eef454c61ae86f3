#version 300 es
// `wireframe`: GLES has no polygon mode, so triangles are drawn unindexed
// (3 vertices each) with the model's index buffer read as the attribute
// a_vertex: each vertex of the draw gets its corner's mesh vertex, whose
// position comes from a texture (16-bit codes in the model's box, 6 bytes a
// vertex); the barycentric corner is gl_VertexID % 3 (each chunk of the draw
// starts at a triangle).
precision highp float;
precision highp int;
precision highp usampler2D;
layout(location = 3) in highp uint a_vertex;
uniform usampler2D u_positions;  // RGB16UI
const int kTextureWidthLog2 = 11;  // texels per row, renderer.cpp's kTextureWidth (shift, not division)
uniform vec3 u_quant_origin;  // object space of code 0
uniform vec3 u_quant_scale;   // object units per code step
uniform mat4 u_model_view;
uniform mat4 u_projection;
out vec3 v_barycentric;
out vec3 v_view_pos;

void main() {
    int corner = gl_VertexID % 3;
    int k = int(a_vertex);
    vec3 p = u_quant_origin + u_quant_scale * vec3(texelFetch(u_positions, ivec2(k & ((1 << kTextureWidthLog2) - 1), k >> kTextureWidthLog2), 0).xyz);
    v_barycentric = vec3(corner == 0, corner == 1, corner == 2);
    vec4 view = u_model_view * vec4(p, 1.0);
    v_view_pos = view.xyz;
    gl_Position = u_projection * view;
}
