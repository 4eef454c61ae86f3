// `baseline`: one flat colour, the benchmark's minimal baseline; shaders
// mesh.vert + baseline.frag.
#include "kiosk/render/styles/styles.h"

namespace body::render {

void draw_baseline(RendererState& s, Frame& f, Model& m) {
    draw_coloured(f, s.programs.baseline, m, m.state.color, false);
}

}  // namespace body::render
