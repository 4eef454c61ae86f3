#pragma once
// The cut plane as the renderer takes it (FrameOptions::cut): a world-space
// plane that removes the geometry on its positive side and caps each cut model
// with its colour (kiosk/render/styles/cut_cap.cpp). The kiosk's plane state
// and gestures are kiosk/app/cut_plane.h.
#include "shared/geometry.h"

namespace body::render {

struct CutPlane {
    bool enabled = false;
    // World plane (n, w), n of unit length: points with dot(n, p) + w > 0 are
    // removed, so n points into the removed half (toward the visitor).
    glm::vec4 plane{0.0f, 0.0f, 1.0f, 0.0f};
    bool caps = true;  // fill each cut model's section with its colour
    // A fixed colour for every cap (diagrams, the golden test); alpha 0: each
    // model's own colour (the selection colour when selected, faded in x-ray).
    glm::vec4 cap_color{0.0f};
    // How much of the bundle's grey-level volume (Renderer::set_cut_volume)
    // shows on the caps: 0 the cap colour only, 1 the grey level only.
    float volume_mix = 0.7f;
    // The volume's grey levels also on the plane around the caps, within the
    // volume's bounds (kiosk/render/volume_plane.cpp): the slice image the
    // sections lie in, hiding what is behind the plane there.
    bool volume_around = false;
};

}  // namespace body::render
