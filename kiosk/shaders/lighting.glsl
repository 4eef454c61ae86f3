// Key/fill/rim lights in view space: unit directions toward the light
// (normalized on the CPU).
uniform vec3 u_key_dir;
uniform vec3 u_fill_dir;
uniform vec3 u_rim_dir;
uniform vec4 u_light_levels;  // key, fill, rim, ambient
// `smooth`: the key and fill directions scaled by their levels, and the
// specular and rim weights (0.25 key, 0.5 rim), so that each term costs no
// multiply per fragment for its level.
uniform vec3 u_key_light;
uniform vec3 u_fill_light;
uniform vec2 u_spec_rim;
// The Blinn-Phong half vector of the key light for the view direction +z
// (normalize(key + (0, 0, 1)), on the CPU): `smooth` takes the eye direction as
// the view axis for its specular and rim terms (see smooth.frag).
uniform vec3 u_half_dir;
// The view ray through this pixel from gl_FragCoord (no view-position varying:
// on a software rasterizer every varying costs per-triangle setup, and a
// million-triangle model has more triangles than covered pixels):
// ray = (fragcoord.xy * u_view_ray.xy + u_view_ray.zw, -1), eye toward the surface.
uniform vec4 u_view_ray;

vec3 view_ray() { return vec3(gl_FragCoord.xy * u_view_ray.xy + u_view_ray.zw, -1.0); }

vec3 facing_normal(vec3 n, vec3 ray) {
    n = normalize(n);
    // Back faces (open meshes, clipped views) are lit as seen.
    return dot(n, ray) > 0.0 ? -n : n;
}
