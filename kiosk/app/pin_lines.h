#pragma once
// The pinned labels' leader lines and anchor dots as 2-D triangles (no GL):
// for each pin with a placed label, a dot on its point and a line to the
// label's nearest edge, in pixels (origin top-left). The overlay draws them
// first in its one draw of solid quads (Overlay::draw's `under`), so they lie
// under the labels and cost no draw call of their own.
#include <vector>

#include "kiosk/app/batch_2d.h"
#include "kiosk/app/kiosk_app.h"

namespace body::kiosk {

class PinLines {
public:
    // Appends the lines and dots of `pins` to `out`; `scale` thickens them on
    // large screens (the overlay's UI scale).
    void append(const std::vector<PinView>& pins, float scale, std::vector<Vertex2d>& out) const;
    // The high-contrast palette's line colours for the next appends (access.h).
    void set_high_contrast(bool on) { high_contrast_ = on; }

private:
    bool high_contrast_ = false;
};

}  // namespace body::kiosk
