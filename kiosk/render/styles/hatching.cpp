// `hatching` and `hatching-2tone`: a tonal art map projected per triangle
// (Praun et al. 2001, Webb et al. 2002; the two-tone threshold variant after
// Lake et al. 2000); shaders mesh.vert + hatching.frag. The tonal art map's
// tones come from kiosk/render/tonal_art_map.cpp; its GL texture is made here.
#include <GLES3/gl3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "kiosk/render/styles/styles.h"
#include "kiosk/render/tonal_art_map.h"

namespace body::render {
namespace {

// Tonal art map (Praun et al. 2001) with our own mip chain (tone matched per
// level), packed so that every fragment needs one texture read: hatching
// blends the two tones around its light level, and layer 0 holds tones 0-3,
// layer 1 tones 2-5 (RGBA), so either layer covers any such pair (the shader
// picks the layer per fragment); layer 2 holds the two tones of the two-tone
// variant (1 and 4, in R and G). Made at the first hatching draw, not at init,
// so that a scene without hatching never pays for generating the tones. The
// CPU tones are freed when it returns.
void create_tonal_art_map(GLuint& texture) {
    TonalArtMap tam = make_tonal_art_map(256, 6);
    constexpr int kLayerTones[3][4] = {{0, 1, 2, 3}, {2, 3, 4, 5}, {1, 4, 4, 4}};
    const auto levels = static_cast<GLsizei>(tam.levels.size());
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, levels, GL_RGBA8, tam.size, tam.size, 3);
    for (GLsizei l = 0; l < levels; ++l) {
        const int size = std::max(1, tam.size >> l);
        const auto& tones = tam.levels[static_cast<size_t>(l)];
        std::vector<uint8_t> rgba(static_cast<size_t>(size) * static_cast<size_t>(size) * 4);
        for (int layer = 0; layer < 3; ++layer) {
            for (size_t i = 0; i < rgba.size() / 4; ++i)
                for (size_t c = 0; c < 4; ++c) rgba[i * 4 + c] = tones[static_cast<size_t>(kLayerTones[layer][c])][i];
            glTexSubImage3D(GL_TEXTURE_2D_ARRAY, l, 0, 0, layer, size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        }
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

}  // namespace

void draw_hatching(RendererState& s, Frame& f, Model& m) {
    Program& p = s.programs.hatching;
    const Lighting& lighting = *f.lighting;
    f.use(p);
    set_matrices(p, f, m);
    set_lights(p, f);
    // Hatch paper tinted lightly by the structure colour.
    Vec3f paper = glm::mix(f.options->paper, m.state.color, 0.25f);
    glUniform4f(p.loc("u_color"), paper.r, paper.g, paper.b, 1.0f);
    if (!s.tam) create_tonal_art_map(s.tam);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, s.tam);
    glUniform1i(p.loc("u_tam"), 0);
    glUniform1f(p.loc("u_hatch_scale"), 1.6f / std::max(m.radius, 1e-6f));
    {
        // The key light in object space: the view direction times the
        // inverse rotation R^T = cbrt(det M) M^-1 of M = mat3(model-view)
        // = s R, so that mesh.vert needs no normal matrix for it.
        const glm::mat3 mv(f.view * m.state.transform);
        const Vec3f key = glm::inverse(mv) * std::cbrt(glm::determinant(mv)) * lighting.key_dir;
        glUniform3fv(p.loc("u_hatch_key"), 1,
                     glm::value_ptr(glm::length(key) > 0.0f ? glm::normalize(key) : Vec3f(0.0f, 0.0f, 1.0f)));
    }
    glUniform1i(p.loc("u_two_tone"), m.state.style == Style::Hatching2Tone ? 1 : 0);
    draw_triangles(f, m);
}

}  // namespace body::render
