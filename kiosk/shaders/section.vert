#version 300 es
// The cut plane's section (kiosk/render/styles/cut_cap.cpp): the fan of the
// plane's crossing segments in the model's object space, drawn into the
// stencil only (even-odd), so any fragment stage links with it.
layout(location = 0) in vec3 a_position;
uniform mat4 u_projection;
uniform mat4 u_model_view;
void main() {
    gl_Position = u_projection * (u_model_view * vec4(a_position, 1.0));
}
