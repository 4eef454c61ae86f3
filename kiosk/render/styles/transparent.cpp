// The transparent pass and the selection: a selected model in the selection
// colour (mesh.vert + smooth.frag) with the white manipulation sphere at its
// centre, unselected models faded by x-ray (mesh.vert + xray.frag). The frame
// (kiosk/render/frame.cpp) draws them back to front with blending on.
#include <GLES3/gl3.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "kiosk/render/styles/styles.h"

namespace body::render {
namespace {

// A depth pre-pass first, so that only the nearest layer of this model blends.
void draw_blended(RendererState& s, Frame& f, Model& m, Program& p, Vec3f color, float alpha, bool lit, Vec3f rim) {
    f.use(p);
    set_matrices(p, f, m);
    if (lit) set_lights(p, f);
    glUniform4f(p.loc("u_color"), color.r, color.g, color.b, alpha);
    glUniform3fv(p.loc("u_rim_color"), 1, glm::value_ptr(rim));
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    draw_triangles(f, m);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_EQUAL);
    draw_triangles(f, m);
    glDepthFunc(GL_LEQUAL);
    s.stats.draw_calls += 2;
    s.stats.triangles += m.index_count / 3;
    ++s.stats.models_drawn;
}

}  // namespace

void draw_selected(RendererState& s, Frame& f, Model& m) {
    draw_blended(s, f, m, s.programs.smooth, f.options->selection_color, 0.55f, true, Vec3f(0.0f));
}

void draw_xray(RendererState& s, Frame& f, Model& m) {
    const Vec3f c = glm::mix(m.state.color, Vec3f(0.55f, 0.62f, 0.75f), 0.5f);
    draw_blended(s, f, m, s.programs.xray, c, 0.10f, false, c * 0.8f);
}

void draw_manipulation_spheres(RendererState& s, Frame& f) {
    Model& sphere = s.models[s.sphere];
    Program& p = s.programs.smooth;
    f.use(p);
    set_lights(p, f);
    glUniform4f(p.loc("u_color"), 0.95f, 0.95f, 0.95f, 1.0f);
    for (auto& [id, m] : s.models) {
        if (m.internal || !m.state.visible || !m.state.selected) continue;
        Vec3f c;
        float r = 0;
        world_sphere(m, c, r);
        sphere.state.transform = glm::scale(glm::translate(glm::mat4(1.0f), c), Vec3f(r * f.options->sphere_fraction));
        set_matrices(p, f, sphere);
        draw_triangles(f, sphere);
        ++s.stats.draw_calls;
    }
}

}  // namespace body::render
