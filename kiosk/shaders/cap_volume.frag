#version 300 es
// The cut plane's cap over the bundle's grey-level volume (scene.json
// cut_plane.volume; kiosk/render/cut_volume.h): the cap colour mixed with the
// source image's grey level at the fragment's position; outside the volume
// the plain cap colour (as baseline.frag). The cap is the plane: no clipping.
precision highp float;
precision mediump sampler3D;
uniform vec4 u_color;
uniform sampler3D u_volume;
uniform mat4 u_view_to_volume;  // view space -> the volume's texture coordinates
uniform float u_volume_mix;     // 0: the cap colour, 1: the grey level
in vec3 v_view;
out vec4 o_color;
void main() {
    vec3 t = (u_view_to_volume * vec4(v_view, 1.0)).xyz;
    vec3 c = u_color.rgb;
    if (all(greaterThanEqual(t, vec3(0.0))) && all(lessThanEqual(t, vec3(1.0))))
        c = mix(c, vec3(texture(u_volume, t).r), u_volume_mix);
    o_color = vec4(c, u_color.a);
}
