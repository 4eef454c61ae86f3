#version 300 es
// The cut plane's cap (kiosk/render/styles/cut_cap.cpp): a square of the plane
// around one model, a 4-vertex strip made from gl_VertexID (no attributes),
// coloured by baseline.frag where the stencil marks that model's section
// (cap_volume.frag: over the bundle's grey-level volume, at v_view).
uniform mat4 u_projection;
uniform vec3 u_center;  // view space
uniform vec3 u_axis_u;  // half sides, view space
uniform vec3 u_axis_v;
out vec3 v_view;
void main() {
    vec2 c = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    v_view = u_center + c.x * u_axis_u + c.y * u_axis_v;
    gl_Position = u_projection * vec4(v_view, 1.0);
}
