// `smooth`: per-pixel Blinn-Phong with key, fill and rim lights (Blinn 1977);
// shaders mesh.vert + smooth.frag.
#include "kiosk/render/styles/styles.h"

namespace body::render {

void draw_smooth(RendererState& s, Frame& f, Model& m) {
    Program& p = s.programs.smooth;
    const Vec3f col = m.state.color;
    f.use(p);
    set_matrices(p, f, m);
    set_lights(p, *f.lighting);
    glUniform4f(p.loc("u_color"), col.r, col.g, col.b, 1.0f);
    draw_triangles(f, m);
}

}  // namespace body::render
