#version 300 es
// `hatching`: a tonal art map of 6 nested tones with mipmaps (Praun et al.
// 2001); the light level picks the weights of the two adjacent tones per
// fragment, white above the lightest (Webb et al. 2002). The map is a 2D array
// texture whose RGBA layers hold tones 0-3 and 2-5, so one read of the layer
// that holds the fragment's two tones replaces the paper's two RGB reads.
// Models carry no texture coordinates, so the map is projected on the
// object-space plane facing the triangle most, one plane per triangle (its
// normal from the screen derivatives of the object position; tone is preserved
// across mip levels, so the coarser samples at plane seams keep the right
// tone). u_two_tone selects the thesis' threshold variant after Lake et al.
// 2000: a light (tone 1) and a dark (tone 4) hatch texture switched at
// N.L = 0.5, both in layer 2 (R, G).
// Cost on a software rasterizer (llvmpipe shades whole 4x4 blocks per small
// triangle, so every operation here counts per triangle): the texture read
// dominates. The view normal is interpolated (no normal matrix per fragment)
// and back faces are culled (no view ray to flip them); the projection plane
// comes from the position's derivatives, so the object normal is not needed.
precision highp float;
in vec3 v_hatch_pos;
in vec3 v_view_normal;
uniform vec4 u_color;
uniform mediump sampler2DArray u_tam;  // layer 0: tones 0-3, 1: tones 2-5 (RGBA), 2: tones 1, 4 (RG)
uniform int u_two_tone;
uniform vec3 u_key_dir;       // unit, toward the key light (view space)
uniform vec4 u_light_levels;  // key, fill, rim, ambient
out vec4 o_color;

void main() {
    float key = dot(v_view_normal, u_key_dir) * inversesqrt(dot(v_view_normal, v_view_normal));
    float light = clamp(u_light_levels.x * max(key, 0.0) + u_light_levels.w, 0.0, 1.0);
    vec3 p = v_hatch_pos;
    vec3 a = abs(cross(dFdx(p), dFdy(p)));
    vec2 uv = a.x >= a.y && a.x >= a.z ? p.yz : (a.y >= a.z ? p.zx : p.xy);
    float s = (1.0 - light) * 6.0;  // 0: white paper .. 6: the darkest tone (tone k - 1 at s = k)
    // Tones with weight > 0 lie within 1 of s: 0-3 for s <= 3.5, 2-5 above.
    bool dark = s > 3.5;
    vec4 tones = texture(u_tam, vec3(uv, u_two_tone != 0 ? 2.0 : (dark ? 1.0 : 0.0)));
    float ink;
    if (u_two_tone != 0) {
        ink = mix(tones.g, tones.r, smoothstep(0.47, 0.53, light));
    } else {
        vec4 k = dark ? vec4(3.0, 4.0, 5.0, 6.0) : vec4(1.0, 2.0, 3.0, 4.0);
        ink = max(0.0, 1.0 - s) + dot(max(vec4(0.0), 1.0 - abs(s - k)), tones);
    }
    o_color = vec4(mix(vec3(0.12, 0.11, 0.10), u_color.rgb, ink), 1.0);
}
