// Key/fill/rim lights in view space: unit directions toward the light
// (normalized on the CPU).
uniform vec3 u_key_dir;
uniform vec3 u_fill_dir;
uniform vec3 u_rim_dir;
uniform vec4 u_light_levels;  // key, fill, rim, ambient

vec3 facing_normal(vec3 n, vec3 view_pos) {
    n = normalize(n);
    // Back faces (open meshes, clipped views) are lit as seen.
    return dot(n, -view_pos) < 0.0 ? -n : n;
}
