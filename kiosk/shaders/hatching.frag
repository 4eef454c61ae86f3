#version 300 es
// `hatching`: a tonal art map of 6 nested tones with mipmaps (Praun et al.
// 2001); the light level, computed per vertex as Praun et al. do and
// interpolated, picks the weights of the two adjacent tones per fragment,
// white above the lightest (Webb et al. 2002). The map is a 2D array
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
// triangle, so every operation here counts per triangle): one varying, the
// position and the tone coordinate sharing a vec4, instead of the normal
// interpolated and normalized per fragment (bench/RESULTS.md). The price: the
// tone is linear across a triangle, so very coarse meshes look darker mid-face.
// Back faces are culled (no view ray to flip them); the projection plane comes
// from the position's derivatives, so the object normal is not needed.
precision highp float;
in vec4 v_hatch;  // xyz: object position in texture repeats, w: tone coordinate 0..6 (mesh.vert)
uniform vec4 u_color;
uniform mediump sampler2DArray u_tam;  // layer 0: tones 0-3, 1: tones 2-5 (RGBA), 2: tones 1, 4 (RG)
uniform int u_two_tone;
out vec4 o_color;
#include "clip.glsl"

void main() {
    float s = v_hatch.w;  // 0: white paper .. 6: the darkest tone (tone k - 1 at s = k)
    vec3 p = v_hatch.xyz;
    vec3 a = abs(cross(dFdx(p), dFdy(p)));
    vec2 uv = a.x >= a.y && a.x >= a.z ? p.yz : (a.y >= a.z ? p.zx : p.xy);
    // Tones with weight > 0 lie within 1 of s: 0-3 for s <= 3.5, 2-5 above.
    bool dark = s > 3.5;
    vec4 tones = texture(u_tam, vec3(uv, u_two_tone != 0 ? 2.0 : (dark ? 1.0 : 0.0)));
    float ink;
    if (u_two_tone != 0) {
        ink = mix(tones.r, tones.g, smoothstep(2.82, 3.18, s));  // light 0.53 .. 0.47
    } else {
        float t = dark ? s - 2.0 : s;  // the layer's channels hold tones at t = 1, 2, 3, 4
        ink = max(0.0, 1.0 - s) + dot(max(vec4(0.0), 1.0 - abs(t - vec4(1.0, 2.0, 3.0, 4.0))), tones);
    }
    clip_fragment();  // after the derivatives, which need every fragment of the quad
    o_color = vec4(mix(vec3(0.12, 0.11, 0.10), u_color.rgb, ink), 1.0);
}
