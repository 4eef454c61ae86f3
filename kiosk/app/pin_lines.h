#pragma once
// Draws the pinned labels' leader lines and anchor dots with GLES 3.0, under
// the overlay (the labels themselves are controls the overlay draws): for each
// pin with a placed label, a dot on its point and a line to the label's
// nearest edge. Needs a current GLES 3 context; one instance per context.
#include <memory>
#include <vector>

#include "kiosk/app/kiosk_app.h"
#include "shared/error.h"

namespace body::kiosk {

class PinLines {
public:
    PinLines();
    ~PinLines();
    PinLines(const PinLines&) = delete;
    PinLines& operator=(const PinLines&) = delete;

    Status init();
    void shutdown();
    // `scale` thickens lines and dots on large screens (the overlay's UI scale).
    void draw(const std::vector<PinView>& pins, float scale, unsigned framebuffer, int width, int height);
    // The high-contrast palette's line colours for the next draws (access.h).
    void set_high_contrast(bool on);

private:
    struct State;
    std::unique_ptr<State> s_;
};

}  // namespace body::kiosk
