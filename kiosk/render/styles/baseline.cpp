// `baseline`: one flat colour, the benchmark's minimal baseline; shaders
// mesh.vert + baseline.frag.
#include "kiosk/render/styles/styles.h"

namespace body::render {

void draw_baseline(RendererState& s, Frame& f, Model& m) {
    Program& p = s.programs.baseline;
    const Vec3f col = m.state.color;
    f.use(p);
    set_matrices(p, f, m);
    glUniform4f(p.loc("u_color"), col.r, col.g, col.b, 1.0f);
    draw_triangles(f, m);
}

}  // namespace body::render
