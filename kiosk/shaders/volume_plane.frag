#version 300 es
// The cut plane around its caps (kiosk/render/volume_plane.cpp): the bundle's
// grey-level volume at the fragment's position; nothing outside the volume.
precision highp float;
precision mediump sampler3D;
uniform sampler3D u_volume;
uniform mat4 u_view_to_volume;  // view space -> the volume's texture coordinates
in vec3 v_view;
out vec4 o_color;
void main() {
    vec3 t = (u_view_to_volume * vec4(v_view, 1.0)).xyz;
    if (any(lessThan(t, vec3(0.0))) || any(greaterThan(t, vec3(1.0)))) discard;
    o_color = vec4(vec3(texture(u_volume, t).r), 1.0);
}
