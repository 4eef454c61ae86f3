// Leader lines and anchor dots: solid triangles in pixel coordinates for the
// overlay's solid draw (contract in pin_lines.h).
#include "kiosk/app/pin_lines.h"

#include <cmath>

#include "kiosk/app/access.h"

namespace body::kiosk {

namespace {

// A segment as a quad `width` pixels wide.
void segment(std::vector<Vertex2d>& out, glm::vec2 a, glm::vec2 b, float width, Rgba c) {
    const glm::vec2 d = b - a;
    const float len = glm::length(d);
    if (len <= 0.0f) return;
    const glm::vec2 n = glm::vec2(-d.y, d.x) / len * (width * 0.5f);
    const glm::vec2 p[4] = {a + n, b + n, b - n, a - n};
    for (int i : {0, 1, 2, 0, 2, 3}) vertex_2d(out, p[i].x, p[i].y, c);
}

// A dot as an octagon of radius r.
void dot(std::vector<Vertex2d>& out, glm::vec2 centre, float r, Rgba c) {
    for (int i = 0; i < 8; ++i) {
        const float a0 = 0.7853982f * static_cast<float>(i), a1 = 0.7853982f * static_cast<float>(i + 1);
        const glm::vec2 p0 = centre + r * glm::vec2(std::cos(a0), std::sin(a0));
        const glm::vec2 p1 = centre + r * glm::vec2(std::cos(a1), std::sin(a1));
        for (const glm::vec2& p : {centre, p0, p1}) vertex_2d(out, p.x, p.y, c);
    }
}

}  // namespace

void PinLines::append(const std::vector<PinView>& pins, float scale, std::vector<Vertex2d>& out) const {
    const Rgba halo = palette(high_contrast_).line_halo, ink = palette(high_contrast_).line_ink;
    for (const PinView& p : pins) {
        if (!p.shown || !p.label) continue;
        const glm::vec2 end = leader_end(*p.label, p.anchor_px);
        segment(out, p.anchor_px, end, 4.0f * scale, halo);  // a light edge keeps the line visible on dark models
        segment(out, p.anchor_px, end, 2.0f * scale, ink);
        dot(out, p.anchor_px, 6.0f * scale, halo);
        dot(out, p.anchor_px, 4.0f * scale, ink);
    }
}

}  // namespace body::kiosk
