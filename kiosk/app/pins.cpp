// Pinned-label layout: greedy placement over a fixed list of candidate places
// (contract in pins.h). Cost O(pins^2 x candidates), a few dozen pins at most.
#include "kiosk/app/pins.h"

#include <algorithm>

namespace body::kiosk {

namespace {

constexpr float kAnchorHalf = 5.0f;  // the square around an anchor no label may cover

Rect candidate(const PinRequest& p, glm::vec2 dir, float distance) {
    Rect r;
    r.w = p.size.x;
    r.h = p.size.y;
    r.x = dir.x > 0 ? p.anchor.x + distance : dir.x < 0 ? p.anchor.x - distance - r.w : p.anchor.x - r.w * 0.5f;
    r.y = dir.y > 0 ? p.anchor.y + distance : dir.y < 0 ? p.anchor.y - distance - r.h : p.anchor.y - r.h * 0.5f;
    return r;
}

bool inside(const Rect& r, const Rect& screen) {
    return r.x >= screen.x && r.y >= screen.y && r.x + r.w <= screen.x + screen.w && r.y + r.h <= screen.y + screen.h;
}

}  // namespace

bool rects_overlap(const Rect& a, const Rect& b, float gap) {
    return a.x < b.x + b.w + gap && b.x < a.x + a.w + gap && a.y < b.y + b.h + gap && b.y < a.y + a.h + gap;
}

std::vector<std::optional<Rect>> layout_pins(std::span<const PinRequest> pins, std::span<const Rect> obstacles,
                                             const Rect& screen, float leader_px, float gap_px) {
    static constexpr glm::vec2 kDirections[] = {{1, -1}, {-1, -1}, {1, 1}, {-1, 1}, {1, 0}, {-1, 0}, {0, -1}, {0, 1}};
    std::vector<Rect> taken(obstacles.begin(), obstacles.end());
    for (const PinRequest& p : pins) {
        taken.push_back(Rect{p.anchor.x - kAnchorHalf, p.anchor.y - kAnchorHalf, 2 * kAnchorHalf, 2 * kAnchorHalf});
    }
    std::vector<std::optional<Rect>> out(pins.size());
    for (size_t i = 0; i < pins.size(); ++i) {
        const PinRequest& p = pins[i];
        if (p.size.x <= 0.0f || p.size.y <= 0.0f) continue;
        for (int step = 1; step <= 3 && !out[i]; ++step) {
            for (const glm::vec2& dir : kDirections) {
                const Rect r = candidate(p, dir, leader_px * static_cast<float>(step));
                if (!inside(r, screen)) continue;
                const bool free = std::none_of(taken.begin(), taken.end(),
                                               [&](const Rect& t) { return rects_overlap(r, t, gap_px); });
                if (!free) continue;
                out[i] = r;
                taken.push_back(r);
                break;
            }
        }
    }
    return out;
}

glm::vec2 leader_end(const Rect& label, const glm::vec2& anchor) {
    return glm::vec2(std::clamp(anchor.x, label.x, label.x + label.w),
                     std::clamp(anchor.y, label.y, label.y + label.h));
}

}  // namespace body::kiosk
