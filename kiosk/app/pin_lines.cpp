// Leader lines and anchor dots: solid triangles in pixel coordinates through
// the shared 2-D batch (batch_2d.h), one draw call per frame (contract in pin_lines.h).
#include "kiosk/app/pin_lines.h"

#include <cmath>

#include "kiosk/app/access.h"
#include "kiosk/app/batch_2d.h"

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

struct PinLines::State {
    Batch2d batch;
    std::vector<Vertex2d> vertices;
    bool high_contrast = false;
};

void PinLines::set_high_contrast(bool on) {
    if (s_) s_->high_contrast = on;
}

PinLines::PinLines() = default;
PinLines::~PinLines() = default;

Status PinLines::init() {
    auto s = std::make_unique<State>();
    if (auto b = s->batch.init("pin lines", Batch2d::Shading::Solid); !b) return b;
    shutdown();
    s_ = std::move(s);
    return ok_status();
}

void PinLines::shutdown() {
    if (!s_) return;
    s_->batch.shutdown();
    s_.reset();
}

void PinLines::draw(const std::vector<PinView>& pins, float scale, unsigned framebuffer, int width, int height) {
    if (!s_) return;
    State& s = *s_;
    s.vertices.clear();
    const Rgba halo = palette(s.high_contrast).line_halo, ink = palette(s.high_contrast).line_ink;
    for (const PinView& p : pins) {
        if (!p.shown || !p.label) continue;
        const glm::vec2 end = leader_end(*p.label, p.anchor_px);
        segment(s.vertices, p.anchor_px, end, 4.0f * scale,
                halo);  // a light edge keeps the line visible on dark models
        segment(s.vertices, p.anchor_px, end, 2.0f * scale, ink);
        dot(s.vertices, p.anchor_px, 6.0f * scale, halo);
        dot(s.vertices, p.anchor_px, 4.0f * scale, ink);
    }
    if (s.vertices.empty()) return;
    s.batch.begin(framebuffer, width, height);
    s.batch.draw(s.vertices);
    s.batch.end();
}

}  // namespace body::kiosk
