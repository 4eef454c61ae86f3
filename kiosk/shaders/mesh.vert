#version 300 es
// Shared vertex stage for the triangle styles (baseline, smooth, hatching,
// paper fill, selection, x-ray): view-space position/normal for lighting and
// object-space position/normal for the triplanar hatching coordinates.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;

out vec3 v_view_pos;
out vec3 v_view_normal;
out vec3 v_object_pos;
out vec3 v_object_normal;

void main() {
    vec4 view = u_model_view * vec4(a_position, 1.0);
    v_view_pos = view.xyz;
    v_view_normal = u_normal_matrix * a_normal;
    v_object_pos = a_position;
    v_object_normal = a_normal;
    gl_Position = u_projection * view;
}
