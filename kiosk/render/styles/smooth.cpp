// `smooth`: per-pixel Blinn-Phong with key, fill and rim lights (Blinn 1977);
// shaders mesh.vert + smooth.frag.
#include "kiosk/render/styles/styles.h"

namespace body::render {

void draw_smooth(RendererState& s, Frame& f, Model& m) { draw_coloured(f, s.programs.smooth, m, m.state.color, true); }

}  // namespace body::render
